"""The Localizer: when it runs, set_pose and its checks, global localization, lost detection, determinism, and
convergence on a synthetic room with ray-cast scans."""

import math

import numpy as np
import pytest
from unit.localization.room import asymmetric_room, drive, path_poses, scan_at

from flex_nav.exceptions import ConfigError
from flex_nav.localization import FilterParams, Kernel, Localizer, LocalizerStatus
from flex_nav.localization.estimate import CONVERGED_FRACTION
from flex_nav.localization.free_space import FREE_MAX
from flex_nav.localization.localizer import warm_up
from flex_nav.nav.planar import compose_poses, inverse_pose

START = (1.5, 1.2, 0.0)
TIGHT = np.diag([0.02**2, 0.02**2, 0.02**2])
AMCL_INITIAL = np.diag([0.25, 0.25, (math.pi / 12) ** 2])  # amcl's initial_cov_xx, _yy, _aa
LAP = [(1.5, 1.2), (4.5, 1.2), (4.5, 2.4), (2.0, 2.4), (2.0, 3.5)]


@pytest.fixture(scope="module")
def grid():
    return asymmetric_room()


def started(grid, params=None, seed=0, pose=START, covariance=TIGHT):
    localizer = Localizer(params or FilterParams(), grid, seed=seed)
    localizer.update((0.0, 0.0, 0.0), None)
    localizer.set_pose(pose, covariance)
    return localizer


def test_uninitialized_until_a_pose_or_global_localization(grid):
    localizer = Localizer(FilterParams(), grid, seed=0)
    estimate = localizer.estimate()
    assert estimate.status is LocalizerStatus.UNINITIALIZED
    assert estimate.particle_count == 0 and localizer.particles.shape == (0, 3)
    assert not localizer.update((0.0, 0.0, 0.0), scan_at(grid, START))
    assert not localizer.update((1.0, 0.0, 0.0), scan_at(grid, START))


def test_first_call_only_stores_the_odometry_then_motion_thresholds(grid):
    params = FilterParams(update_min_d=0.1, update_min_a=0.2)
    localizer = Localizer(params, grid, seed=0)
    localizer.set_pose(START, TIGHT)
    scan = scan_at(grid, START)
    assert not localizer.update((5.0, 5.0, 1.0), scan)  # first call: stored
    assert localizer.update((5.0, 5.0, 1.0), scan)  # the scan after set_pose is weighed without motion
    assert not localizer.update((5.05, 5.0, 1.0), scan)  # 5 cm < update_min_d
    assert not localizer.update((5.1, 5.0, 1.0), None)  # no scan
    assert localizer.update((5.11, 5.0, 1.0), scan)  # 11 cm since the last update
    assert not localizer.update((5.11, 5.0, 1.15), scan)
    assert localizer.update((5.11, 5.0, 1.25), scan)  # 0.25 rad
    assert not localizer.update((5.11, 5.0, 1.25), scan)
    localizer.request_nomotion_update()
    assert localizer.update((5.11, 5.0, 1.25), scan)
    assert not localizer.update((5.11, 5.0, 1.25), scan)


def test_set_pose_count_between_min_and_max_and_read_only_views(grid):
    params = FilterParams(min_particles=200, max_particles=3000)
    tight = started(grid, params, covariance=np.zeros((3, 3)))
    assert tight.estimate().particle_count == 200
    wide = started(grid, params, covariance=AMCL_INITIAL)
    assert 200 < wide.estimate().particle_count <= 3000
    estimate = wide.estimate()
    assert estimate.status is LocalizerStatus.LOCALIZED
    assert estimate.pose[0] == pytest.approx(START[0], abs=0.05) and estimate.pose[1] == pytest.approx(START[1],
                                                                                                          abs=0.05)
    np.testing.assert_allclose(estimate.covariance, AMCL_INITIAL, rtol=0.15, atol=0.01)
    assert wide.weights.sum() == pytest.approx(1.0)
    with pytest.raises(ValueError, match="read-only"):
        wide.particles[0, 0] = 1.0
    with pytest.raises(ValueError, match="read-only"):
        wide.weights[0] = 1.0


@pytest.mark.parametrize(
    ("pose", "covariance", "message"),
    [
        ((math.nan, 0.0, 0.0), TIGHT, "set_pose: pose must be a finite"),
        ((0.0, 0.0), TIGHT, "set_pose: pose must be a finite"),
        (START, np.diag([0.1, math.nan, 0.1]), "covariance must be finite"),
        (START, np.eye(2), r"covariance must be \(3, 3\)"),
        (START, np.array([[0.1, 0.05, 0], [0.0, 0.1, 0], [0, 0, 0.1]]), "covariance must be symmetric"),
        (START, np.array([[0.1, 0.2, 0], [0.2, 0.1, 0], [0, 0, 0.1]]), "covariance must be positive semi-definite"),
        (START, np.diag([0.1, -0.1, 0.1]), "covariance must be positive semi-definite"),
    ],
)
def test_set_pose_refuses_bad_input(grid, pose, covariance, message):
    localizer = Localizer(FilterParams(), grid, seed=0)
    with pytest.raises(ConfigError, match=message):
        localizer.set_pose(pose, covariance)
    assert localizer.estimate().status is LocalizerStatus.UNINITIALIZED


def test_non_finite_odometry_is_refused(grid):
    with pytest.raises(ConfigError, match="update: odom must be a finite"):
        started(grid).update((0.0, math.inf, 0.0), None)


def test_dropped_beams_are_counted(grid):
    localizer = started(grid)
    scan = scan_at(grid, START)
    ranges = scan.ranges.copy()
    ranges[:7] = math.nan
    ranges[7:10] = 100.0
    assert localizer.update((0.0, 0.0, 0.0), scan._replace(ranges=ranges))
    assert localizer.last_dropped_beams == 10 + int((~np.isfinite(scan.ranges[10:])).sum())


def test_resampling_every_resample_interval_updates(grid):
    traces = {}
    for interval in (1, 2):
        params = FilterParams(resample_interval=interval, odom_alpha1=0.0, odom_alpha2=0.0, odom_alpha3=0.0,
                              odom_alpha4=0.0)  # without motion noise, resampled copies stay identical
        localizer = started(grid, params, covariance=AMCL_INITIAL)
        trace = []
        for step in range(1, 4):
            localizer.update((0.1 * step, 0.0, 0.0), scan_at(grid, (START[0] + 0.1 * step, START[1], 0.0)))
            particles = localizer.particles
            trace.append(len(np.unique(particles, axis=0)) < len(particles))
        traces[interval] = trace
    # resampled at the start of the update after the one that made it due
    assert traces[1] == [False, True, True]
    assert traces[2] == [False, False, True]


def test_global_localization_samples_only_free_cells(grid):
    params = FilterParams(max_particles=4000)
    localizer = Localizer(params, grid, seed=0)
    localizer.global_localization()
    particles = localizer.particles
    assert particles.shape == (4000, 3)
    rows, cols = grid.world_to_cells(particles[:, 0], particles[:, 1])
    values = grid.occupancy[rows, cols]
    assert ((values >= 0) & (values <= FREE_MAX)).all()
    assert localizer.estimate().status is LocalizerStatus.LOST


def test_lost_when_the_spread_passes_lost_std_xy_and_back_by_set_pose(grid):
    params = FilterParams(lost_std_xy=0.1)
    localizer = started(grid, params, covariance=np.diag([0.3**2, 0.3**2, 0.01]))
    assert localizer.estimate().status is LocalizerStatus.LOCALIZED  # a given pose is trusted at first
    # the scans do not fit anywhere near: the cloud stays wide
    localizer.update((0.0, 0.0, 0.0), scan_at(grid, START)._replace(ranges=np.full(271, 0.3)))
    assert localizer.estimate().status is LocalizerStatus.LOST
    localizer.set_pose(START, TIGHT)
    assert localizer.estimate().status is LocalizerStatus.LOCALIZED


def test_converged_global_localization_leaves_lost(grid):
    localizer = Localizer(FilterParams(), grid, seed=2)
    localizer.global_localization()
    errors = drive(localizer, grid, path_poses(LAP[:3]), np.random.default_rng(2))
    estimate = localizer.estimate()
    assert estimate.status is LocalizerStatus.LOCALIZED
    spread = math.sqrt(np.linalg.eigvalsh(estimate.covariance[:2, :2]).max())
    assert spread <= CONVERGED_FRACTION * FilterParams().lost_std_xy
    assert errors[-1] < 0.05


def test_tracks_the_lap_within_a_few_cm(grid):
    localizer = started(grid)
    errors = np.array(drive(localizer, grid, path_poses(LAP), np.random.default_rng(3)))
    assert np.median(errors) < 0.02 and errors.max() < 0.06
    assert localizer.estimate().status is LocalizerStatus.LOCALIZED


@pytest.mark.parametrize("seed", [0, 1, 2])
@pytest.mark.parametrize("offset", [(1.0, 0.0, 30.0), (0.0, 1.0, -30.0), (-0.7, 0.7, 30.0)])
def test_converges_from_1_m_and_30_deg_off(grid, seed, offset):
    dx, dy, dyaw = offset
    localizer = started(grid, seed=seed, pose=(START[0] + dx, START[1] + dy, math.radians(dyaw)),
                        covariance=AMCL_INITIAL)
    path = path_poses(LAP[:2])  # 3 m straight
    errors = drive(localizer, grid, path, np.random.default_rng(seed))
    assert max(errors[40:]) < 0.05  # within 5 cm after 2 m of driving, and staying


@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_global_localization_converges(grid, seed):
    localizer = Localizer(FilterParams(), grid, seed=seed)
    localizer.global_localization()
    errors = drive(localizer, grid, path_poses(LAP), np.random.default_rng(seed))
    assert max(errors[60:]) < 0.05  # within 5 cm after 3 m of driving, and staying
    assert localizer.estimate().status is LocalizerStatus.LOCALIZED


def test_deterministic_for_a_seed(grid):
    runs = []
    for seed in (5, 5, 6):
        localizer = started(grid, seed=seed, covariance=AMCL_INITIAL)
        drive(localizer, grid, path_poses(LAP[:2])[:30], np.random.default_rng(0))
        runs.append(localizer.particles.copy())
    np.testing.assert_array_equal(runs[0], runs[1])
    assert runs[0].shape != runs[2].shape or not np.array_equal(runs[0], runs[2])


def test_numpy_kernel_gives_the_same_filter(grid):
    estimates = []
    for kernel in Kernel:
        localizer = Localizer(FilterParams(), grid, seed=4, kernel=kernel)
        localizer.update((0.0, 0.0, 0.0), None)
        localizer.set_pose(START, AMCL_INITIAL)
        drive(localizer, grid, path_poses(LAP[:2])[:20], np.random.default_rng(4))
        estimates.append(localizer.estimate())
    np.testing.assert_allclose(estimates[0].pose, estimates[1].pose, atol=1e-9)
    assert estimates[0].particle_count == estimates[1].particle_count


def test_set_map_keeps_the_particles(grid):
    localizer = started(grid)
    before = localizer.particles.copy()
    other = grid.copy()
    other.occupancy[:, :] = 0
    localizer.set_map(other)
    np.testing.assert_array_equal(localizer.particles, before)
    assert localizer.field.grid is other


def test_warm_up_runs_the_kernels():
    assert 0.0 < warm_up() < 120.0


def test_restart_odometry_applies_no_motion_across_the_break(grid):
    localizer = started(grid)
    scan = scan_at(grid, START)
    assert localizer.update((0.0, 0.0, 0.0), scan)
    before = localizer.particles.copy()
    localizer.restart_odometry()
    assert not localizer.update((-7.0, 3.0, 2.0), scan)  # a restarted odometry source: only stored
    np.testing.assert_array_equal(localizer.particles, before)
    assert localizer.update((-6.9, 3.0, 2.0), scan)  # 10 cm from the new reference


def kidnapped(grid, params=None, seed=0, updates=12):
    """A filter tracking at START, then the robot is carried to another pose: odometry moves on 6 cm a step as
    if it were still driving east from START, the scans come from the new place (driving north). Returns the filter
    and its status after each update."""
    localizer = started(grid, params, seed=seed)
    rng = np.random.default_rng(seed)
    localizer.update((0.0, 0.0, 0.0), scan_at(grid, START))
    for i in range(1, 6):
        assert localizer.update((0.06 * i, 0.0, 0.0), scan_at(grid, (START[0] + 0.06 * i, START[1], 0.0), rng, 0.01))
    assert localizer.status is LocalizerStatus.LOCALIZED
    elsewhere = (4.0, 1.2, math.pi / 2)
    statuses = []
    for i in range(1, updates + 1):
        odom = (0.3 + 0.06 * i, 0.0, 0.0)
        truth = (elsewhere[0], elsewhere[1] + 0.06 * i, elsewhere[2])
        assert localizer.update(odom, scan_at(grid, truth, rng, 0.01))
        statuses.append(localizer.status)
    return localizer, statuses


def test_kidnapped_robot_is_lost_within_the_match_window(grid):
    localizer, statuses = kidnapped(grid)
    first_lost = statuses.index(LocalizerStatus.LOST)
    assert first_lost <= FilterParams().lost_match_updates  # the window of fractions, no more
    assert localizer.match_fraction < FilterParams().lost_match_fraction


def test_kidnapped_tight_cloud_stays_lost_while_the_scans_do_not_fit(grid):
    localizer, statuses = kidnapped(grid, updates=30)
    first_lost = statuses.index(LocalizerStatus.LOST)
    assert all(s is LocalizerStatus.LOST for s in statuses[first_lost:]) or (
        # it may find the new place by itself (the cloud spread); then only where the scans fit
        localizer.match_fraction_mean >= FilterParams().converged_match_fraction
    )


def test_spread_rule_alone_misses_the_kidnap(grid):
    params = FilterParams(lost_match_fraction=0.0, converged_match_fraction=0.0)  # the match rule off
    localizer, statuses = kidnapped(grid, params, updates=8)
    assert LocalizerStatus.LOST not in statuses  # what the match rule is for: the cloud stays tight
    assert localizer.match_fraction < FilterParams().lost_match_fraction


def test_unmapped_things_blocking_part_of_the_scan_are_no_kidnap(grid):
    localizer = started(grid)
    rng = np.random.default_rng(4)
    poses = path_poses(LAP[:2])
    odom = (0.0, 0.0, 0.0)
    for before, after in zip(poses[:-1], poses[1:]):
        odom = compose_poses(odom, compose_poses(inverse_pose(before), after))
        scan = scan_at(grid, after, rng, 0.01)
        ranges = scan.ranges.copy()
        ranges[100:190] = np.minimum(ranges[100:190], 0.6)  # a third of the view blocked 60 cm ahead (a person)
        localizer.update(odom, scan._replace(ranges=ranges))
        assert localizer.status is LocalizerStatus.LOCALIZED
    assert 0.5 < localizer.match_fraction_mean < 0.8


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_global_localization_standing_still_converges_on_the_pose(grid, seed):
    localizer = Localizer(FilterParams(), grid, seed=seed)
    localizer.update((0.0, 0.0, 0.0), None)
    localizer.global_localization()
    rng = np.random.default_rng(seed)
    for _ in range(100):
        localizer.request_nomotion_update()
        assert localizer.update((0.0, 0.0, 0.0), scan_at(grid, START, rng, 0.01))
        if localizer.status is LocalizerStatus.LOCALIZED:
            break
    assert localizer.status is LocalizerStatus.LOCALIZED
    x, y, yaw = localizer.estimate().pose
    assert math.hypot(x - START[0], y - START[1]) < 0.05 and abs(yaw - START[2]) < math.radians(3.0)
    assert localizer.match_fraction_mean >= FilterParams().converged_match_fraction


def test_lost_filter_with_a_tight_cloud_returns_only_where_the_scans_fit(grid):
    # a tight cloud 30 cm off the robot, declared lost: the cloud is tight but the scans do not fit it
    localizer = started(grid, pose=(START[0] + 0.3, START[1], 0.0))
    localizer._status = LocalizerStatus.LOST  # as after a kidnap
    rng = np.random.default_rng(1)
    statuses = []
    for _ in range(40):
        localizer.request_nomotion_update()
        localizer.update((0.0, 0.0, 0.0), scan_at(grid, START, rng, 0.01))
        x, _, _ = localizer.estimate().pose
        statuses.append((localizer.status, abs(x - START[0])))
    assert all(status is LocalizerStatus.LOST for status, _ in statuses[:10])
    assert all(error < 0.1 for status, error in statuses if status is LocalizerStatus.LOCALIZED)


def test_match_fraction_is_nan_before_a_sensor_update(grid):
    localizer = started(grid)
    assert math.isnan(localizer.match_fraction) and math.isnan(localizer.match_fraction_mean)


def test_set_map_forgets_the_match_fractions(grid):
    localizer = started(grid)
    localizer.update((0.0, 0.0, 0.0), scan_at(grid, START))
    assert localizer.match_fraction_mean == pytest.approx(1.0)
    localizer.set_map(grid)
    assert math.isnan(localizer.match_fraction_mean)


def test_reseed_restarts_the_draws_whatever_was_drawn_before(grid):
    """A localizer that has drawn more (a longer wait before a run) starts from the same cloud after reseed."""
    cov = np.diag([0.01, 0.01, 0.01])
    fresh = Localizer(FilterParams(min_particles=100, max_particles=500), grid, seed=7)
    used = Localizer(FilterParams(min_particles=100, max_particles=500), grid, seed=7)
    used.set_pose((1.0, 1.0, 0.0), cov)  # draws that fresh has not made
    used.reseed(7)
    fresh.reseed(7)
    used.set_pose((1.5, 1.0, 0.2), cov)
    fresh.set_pose((1.5, 1.0, 0.2), cov)
    np.testing.assert_array_equal(used.particles, fresh.particles)
    other = Localizer(FilterParams(min_particles=100, max_particles=500), grid, seed=8)
    other.set_pose((1.5, 1.0, 0.2), cov)
    assert not np.array_equal(other.particles, fresh.particles)
