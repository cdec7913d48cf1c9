"""flex_nav.resources: the data folders are found in a source checkout, under an install prefix's share/flex_nav,
or where FLEX_NAV_SHARE says; a missing install is a ConfigError naming where it looked."""

from __future__ import annotations

from pathlib import Path

import pytest

from flex_nav import resources
from flex_nav.exceptions import ConfigError

REPO = Path(__file__).resolve().parents[2]


def test_a_source_checkout_uses_its_own_folders(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv(resources.SHARE_ENV, raising=False)
    assert resources.share_dir() == REPO
    assert (resources.behaviors_dir() / "flex_planner.yaml").is_file()
    assert (resources.models_dir() / "obstacle_classifier.onnx").is_file()


def test_an_installed_package_finds_prefix_share(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # pip puts the module in <prefix>/lib/python3.X/site-packages/flex_nav and data_files in <prefix>/share/flex_nav
    module = tmp_path / "lib" / "python3.11" / "site-packages" / "flex_nav" / "resources.py"
    (tmp_path / "share" / "flex_nav" / "behaviors").mkdir(parents=True)
    monkeypatch.delenv(resources.SHARE_ENV, raising=False)
    monkeypatch.setattr(resources, "_HERE", module)
    assert resources.share_dir() == tmp_path / "share" / "flex_nav"


def test_the_environment_overrides(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    (tmp_path / "behaviors").mkdir()
    monkeypatch.setenv(resources.SHARE_ENV, str(tmp_path))
    assert resources.share_dir() == tmp_path


def test_nothing_installed_names_where_it_looked(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv(resources.SHARE_ENV, raising=False)
    monkeypatch.setattr(resources, "_HERE", tmp_path / "site-packages" / "flex_nav" / "resources.py")
    with pytest.raises(ConfigError, match=r"not installed; looked in .*FLEX_NAV_SHARE"):
        resources.share_dir()
