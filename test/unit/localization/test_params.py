"""FilterParams: defaults valid, every check names the field and the bad value, from_mapping's unknown keys."""

import dataclasses

import pytest

from flex_nav.exceptions import ConfigError
from flex_nav.localization import FilterParams


def test_defaults_are_valid_and_frozen():
    params = FilterParams()
    assert params.min_particles <= params.max_particles
    with pytest.raises(dataclasses.FrozenInstanceError):
        params.min_particles = 1  # type: ignore[misc]


@pytest.mark.parametrize(
    ("changes", "message"),
    [
        ({"min_particles": 6000}, "localization: min_particles must be <= max_particles (5000), got 6000"),
        ({"min_particles": 0}, "localization: min_particles must be an integer >= 1, got 0"),
        ({"max_particles": 2.0}, "localization: max_particles must be an integer >= 1, got 2.0"),
        ({"kld_err": 0.0}, "localization: kld_err must be > 0, got 0.0"),
        ({"kld_z": float("nan")}, "localization: kld_z must be a finite number, got nan"),
        ({"odom_alpha3": -0.1}, "localization: odom_alpha3 must be >= 0.0, got -0.1"),
        ({"laser_z_hit": 1.5}, "localization: laser_z_hit must be <= 1.0, got 1.5"),
        ({"laser_z_rand": 0.0}, "localization: laser_z_rand must be > 0, got 0.0"),
        ({"laser_sigma_hit": 0.0}, "localization: laser_sigma_hit must be > 0 [m], got 0.0"),
        ({"laser_likelihood_max_dist": -1.0}, "localization: laser_likelihood_max_dist must be > 0 [m], got -1.0"),
        ({"laser_max_beams": 1}, "localization: laser_max_beams must be an integer >= 2, got 1"),
        ({"update_min_d": -0.1}, "localization: update_min_d must be >= 0.0 [m], got -0.1"),
        ({"update_min_a": 7.0}, "localization: update_min_a must be <= 6.283185307179586 [rad], got 7.0"),
        ({"resample_interval": 0}, "localization: resample_interval must be an integer >= 1, got 0"),
        ({"recovery_alpha_slow": 0.1, "recovery_alpha_fast": 0.001},
         "localization: recovery_alpha_slow must be > 0 and < recovery_alpha_fast (0.001) for random particles, "
         "or both 0 to disable them, got 0.1"),
        ({"recovery_alpha_fast": 0.1},
         "localization: recovery_alpha_slow must be > 0 and < recovery_alpha_fast (0.1) for random particles, "
         "or both 0 to disable them, got 0.0"),
        ({"lost_std_xy": 0.0}, "localization: lost_std_xy must be > 0 [m], got 0.0"),
        ({"lost_match_distance": 0.0}, "localization: lost_match_distance must be > 0 [m], got 0.0"),
        ({"lost_match_fraction": 1.5}, "localization: lost_match_fraction must be <= 1.0, got 1.5"),
        ({"lost_match_updates": 0}, "localization: lost_match_updates must be an integer >= 1, got 0"),
        ({"lost_match_updates": 5.0}, "localization: lost_match_updates must be an integer >= 1, got 5.0"),
        ({"converged_match_fraction": -0.1}, "localization: converged_match_fraction must be >= 0.0, got -0.1"),
        ({"lost_match_fraction": 0.7, "converged_match_fraction": 0.6},
         "localization: converged_match_fraction must be >= lost_match_fraction (0.7), got 0.6"),
    ],
)
def test_bad_values_name_the_field_and_the_value(changes, message):
    with pytest.raises(ConfigError) as err:
        FilterParams(**changes)
    assert str(err.value) == message


def test_from_mapping_takes_amcl_names_and_integers_for_floats():
    params = FilterParams.from_mapping({"min_particles": 100, "max_particles": 2000, "kld_err": 0.05,
                                        "update_min_d": 1, "laser_max_beams": 30, "lost_match_updates": 3,
                                        "lost_match_fraction": 0}, "amcl")
    assert params.min_particles == 100 and params.max_particles == 2000
    assert params.update_min_d == 1.0 and isinstance(params.update_min_d, float)
    assert params.laser_max_beams == 30
    assert params.lost_match_updates == 3 and params.lost_match_fraction == 0.0


def test_from_mapping_unknown_key_lists_the_valid_names():
    with pytest.raises(ConfigError) as err:
        FilterParams.from_mapping({"odom_model_type": "diff-corrected"}, "amcl")
    text = str(err.value)
    assert text.startswith("amcl: parameter 'odom_model_type' is not valid (valid: min_particles, max_particles,")
    assert "lost_std_xy" in text


def test_from_mapping_bad_value_names_the_owner():
    with pytest.raises(ConfigError, match=r"^amcl: localization: kld_err must be > 0, got -1.0$"):
        FilterParams.from_mapping({"kld_err": -1}, "amcl")
