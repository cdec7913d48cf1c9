"""The localizer's parameters: one frozen record, validated once when built.

Field names are amcl's ROS parameter names where the meaning is the same, so a node can read them from the
parameter server under the names amcl users know. Where a default differs from amcl's, the comment says
why (tuned on the simulated TurtleBot 2, Create 2 and TurtleBot 4 in the lab world with
``bench/bench_localization_accuracy.py``; the figures are in bench/README.md).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping

from flex_nav import validation
from flex_nav.exceptions import ConfigError


@dataclass(frozen=True)
class FilterParams:
    """Parameters of :class:`flex_nav.localization.Localizer` (units in the comments)."""

    # --- particle count: KLD-sampling (Fox 2003) between the two bounds
    min_particles: int = 500  # amcl's default
    max_particles: int = 5000  # amcl's default
    kld_err: float = 0.01  # [-] bound on the KL divergence between sample and true posterior (amcl's default)
    kld_z: float = 0.99  # [-] the standard normal quantile z_(1-delta) used in the bound, as amcl uses it
    # --- odometry motion model (amcl's diff-corrected): variance per squared motion
    # amcl's defaults are 0.2 each. Rotation noise from rotation is far smaller here (the simulated robots' odometry
    # turns to 2-5 %); the noise from translation stays large enough that a cloud which settled a few cm off
    # (after a rough initial pose) drifts onto the scans within a second or two.
    odom_alpha1: float = 0.05  # [rad²/rad²] rotation noise from rotation (amcl: 0.2)
    odom_alpha2: float = 0.2  # [rad²/m²] rotation noise from translation (amcl's default)
    odom_alpha3: float = 0.1  # [m²/m²] translation noise from translation (amcl: 0.2)
    odom_alpha4: float = 0.02  # [m²/rad²] translation noise from rotation (amcl: 0.2)
    # --- likelihood-field laser model
    laser_z_hit: float = 0.95  # [-] weight of the Gaussian around the nearest obstacle (amcl's default)
    laser_z_rand: float = 0.05  # [-] weight of the uniform floor z_rand / range_max (amcl's default)
    laser_sigma_hit: float = 0.03  # [m] amcl: 0.2. The simulated lidars are accurate to about 1 cm and the maps
    #   rasterise the world at 5 cm: a narrow Gaussian separates poses a cm apart (0.05 m: p95 error 3.5 cm instead
    #   of 2.4 cm on the lab lap). A rough start is not lost by it: the model widens it while the cloud is wide
    #   (sensor_model.annealed_sigma)
    laser_likelihood_max_dist: float = 2.0  # [m] distances are capped here (amcl's default)
    laser_max_beams: int = 60  # amcl: 30. Twice the beams, twice the evidence per update; still ~1 ms
    # --- when the filter runs
    update_min_d: float = 0.05  # [m] amcl: 0.2. An update every 5 cm (every scan at 0.5 m/s) keeps the error small
    update_min_a: float = 0.05  # [rad] amcl: pi/6
    resample_interval: int = 1  # [sensor updates] amcl: 2. Resampling every update follows the scans closest
    # --- random particles (Augmented MCL); 0 and 0 disable it, as amcl's defaults do
    recovery_alpha_slow: float = 0.0  # [-] e.g. 0.001
    recovery_alpha_fast: float = 0.0  # [-] e.g. 0.1
    # --- status (not in amcl)
    lost_std_xy: float = 0.5  # [m] spread of the cloud above which the filter reports itself lost
    # scan consistency (consistency.py): the share of beams ending within lost_match_distance of a mapped obstacle,
    # seen from the estimate, averaged over lost_match_updates updates of a tight cloud. Below lost_match_fraction a
    # localized filter is lost (a kidnapped robot); a lost one is localized again only at converged_match_fraction.
    # On the right pose the lab lap's worst mean was 0.78 (TurtleBot 4 in people crossing, s6); a kidnapped cloud
    # fell to 0.1-0.3 (bench_localization_accuracy.py, bench/README.md)
    lost_match_distance: float = 0.1  # [m] (two cells of a 5 cm map: map rasterisation, range noise, a cm of error)
    lost_match_fraction: float = 0.5  # [-]
    lost_match_updates: int = 5  # [updates] (0.5 s at 0.5 m/s with an update every 5 cm; every scan standing still)
    converged_match_fraction: float = 0.85  # [-]

    def __post_init__(self) -> None:
        owner = "localization"
        validation.integer(owner, "min_particles", self.min_particles, minimum=1)
        validation.integer(owner, "max_particles", self.max_particles, minimum=1)
        if self.min_particles > self.max_particles:
            raise ConfigError(
                f"{owner}: min_particles must be <= max_particles ({self.max_particles}), got {self.min_particles}"
            )
        validation.number(owner, "kld_err", self.kld_err, positive=True, maximum=1.0)
        validation.number(owner, "kld_z", self.kld_z, positive=True, maximum=10.0)
        for name in ("odom_alpha1", "odom_alpha2", "odom_alpha3", "odom_alpha4"):
            validation.number(owner, name, getattr(self, name), minimum=0.0)
        validation.number(owner, "laser_z_hit", self.laser_z_hit, minimum=0.0, maximum=1.0)
        validation.number(owner, "laser_z_rand", self.laser_z_rand, minimum=0.0, maximum=1.0)
        if not self.laser_z_rand > 0.0:
            # the floor keeps every particle's likelihood > 0: one stray beam must not zero a good pose
            raise ConfigError(f"{owner}: laser_z_rand must be > 0, got {self.laser_z_rand!r}")
        validation.number(owner, "laser_sigma_hit", self.laser_sigma_hit, positive=True, unit="[m]")
        validation.number(owner, "laser_likelihood_max_dist", self.laser_likelihood_max_dist, positive=True,
                          unit="[m]")
        validation.integer(owner, "laser_max_beams", self.laser_max_beams, minimum=2)
        validation.number(owner, "update_min_d", self.update_min_d, minimum=0.0, unit="[m]")
        validation.number(owner, "update_min_a", self.update_min_a, minimum=0.0, maximum=2.0 * math.pi,
                          unit="[rad]")
        validation.integer(owner, "resample_interval", self.resample_interval, minimum=1)
        validation.number(owner, "recovery_alpha_slow", self.recovery_alpha_slow, minimum=0.0, maximum=1.0)
        validation.number(owner, "recovery_alpha_fast", self.recovery_alpha_fast, minimum=0.0, maximum=1.0)
        slow, fast = self.recovery_alpha_slow, self.recovery_alpha_fast
        if (slow > 0.0 or fast > 0.0) and not 0.0 < slow < fast:
            raise ConfigError(
                f"{owner}: recovery_alpha_slow must be > 0 and < recovery_alpha_fast ({fast}) for random "
                f"particles, or both 0 to disable them, got {slow}"
            )
        validation.number(owner, "lost_std_xy", self.lost_std_xy, positive=True, unit="[m]")
        validation.number(owner, "lost_match_distance", self.lost_match_distance, positive=True, unit="[m]")
        validation.number(owner, "lost_match_fraction", self.lost_match_fraction, minimum=0.0, maximum=1.0)
        validation.integer(owner, "lost_match_updates", self.lost_match_updates, minimum=1)
        validation.number(owner, "converged_match_fraction", self.converged_match_fraction, minimum=0.0,
                          maximum=1.0)
        if self.converged_match_fraction < self.lost_match_fraction:
            raise ConfigError(
                f"{owner}: converged_match_fraction must be >= lost_match_fraction ({self.lost_match_fraction}), "
                f"got {self.converged_match_fraction}"
            )

    @classmethod
    def from_mapping(cls, values: Mapping[str, Any], owner: str) -> FilterParams:
        """Params from a dict (e.g. a node's private ROS parameters); ``owner`` (``"amcl"``, a node name) starts
        the message of an unknown key, which lists the valid names. An integer given for a float field is taken;
        a float for an integer field is refused by the field's check."""
        return validation.dataclass_from_mapping(cls, values, owner)
