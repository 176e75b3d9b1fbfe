"""The robot file's ``chain`` block: an arm's own transforms, kept exactly."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import yaml
from support.urdf import URDF_DIR

import kinematica as km
from kinematica.errors import RobotFileError


@pytest.fixture(scope="module")
def kr16():
    return km.load(URDF_DIR / "kuka_kr16_2.urdf")


@pytest.mark.parametrize("suffix", [".yaml", ".json", ".toml"])
def test_a_urdf_robot_saved_and_read_back_is_the_same_arm(kr16, tmp_path, suffix):
    path = tmp_path / f"kr16{suffix}"
    kr16.save(path)
    back = km.load(path)
    assert back.transforms is not None
    q = kr16.random_q(30, seed=1)
    np.testing.assert_array_equal(back.fk(q), kr16.fk(q))
    assert [link.a for link in back.links] == [link.a for link in kr16.links]


def test_a_dh_robot_has_no_chain_block(tmp_path):
    path = tmp_path / "puma.yaml"
    km.load("puma560").save(path)
    assert "chain" not in yaml.safe_load(path.read_text())


def _data(kr16, tmp_path):
    path = tmp_path / "kr16.yaml"
    kr16.save(path)
    return yaml.safe_load(path.read_text())


def _load(data, tmp_path):
    path = tmp_path / "edited.yaml"
    path.write_text(yaml.safe_dump(data))
    return km.load(path)


def test_chain_block_errors_name_the_key(kr16, tmp_path):
    data = _data(kr16, tmp_path)
    data["chain"]["between"] = data["chain"]["between"][:-1]
    with pytest.raises(RobotFileError, match=r"chain\.between.*expected a list of 5 frames"):
        _load(data, tmp_path)
    data = _data(kr16, tmp_path)
    del data["chain"]["end"]
    with pytest.raises(RobotFileError, match=r"chain.*missing end"):
        _load(data, tmp_path)
    data = _data(kr16, tmp_path)
    data["chain"]["frames"][2]["matrix"][0][0] = 2.0
    with pytest.raises(RobotFileError, match=r"chain\.frames\[2\]\.matrix.*not a rotation"):
        _load(data, tmp_path)
    data = _data(kr16, tmp_path)
    data["chain"]["ends"] = data["chain"].pop("end")
    with pytest.raises(RobotFileError, match="did you mean 'end'"):
        _load(data, tmp_path)


def test_far_common_normals_are_no_unit_slip_with_a_chain(kr16, tmp_path):
    data = _data(kr16, tmp_path)
    data["joints"][1]["d"] = 250.0  # a DH table describing nearly parallel axes
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        _load(data, tmp_path)
    del data["chain"]
    with pytest.warns(km.UnitWarning, match="longer than 20 m"):
        _load(data, tmp_path)
