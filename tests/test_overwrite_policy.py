"""The overwrite policy has no holes: sidecars go with their file, an empty name is no
folder, and the API's file writers refuse an existing file too."""

from __future__ import annotations

import pytest

import railhunt
from test_cli import assert_input_error, run
from test_cli_robustness import WRITERS, _args, _flag, forbid

PAPER = railhunt.Vehicle.paper2019()

CSV_WRITERS = [w for w in WRITERS if _flag(w[0]) == "--csv"]
STUDY_WRITERS = [w for w in WRITERS if _flag(w[0]) == "--out" and w[0][0] != "plot"]


@pytest.mark.parametrize(("args", "target"), CSV_WRITERS, ids=lambda v: " ".join(v)
                         if isinstance(v, list) else None)  # fmt: skip
def test_an_existing_metadata_sidecar_is_kept_without_overwrite(tmp_path, monkeypatch, args,
                                                                target):  # fmt: skip
    csv = tmp_path / "new.csv"
    side = tmp_path / "new.csv.meta.json"
    side.write_text("keep me")
    forbid(monkeypatch, target)
    assert_input_error(run(*_args(args, csv, tmp_path)), "--csv", str(side), "exists",
                       "--overwrite")  # fmt: skip
    assert side.read_text() == "keep me" and not csv.exists()


def test_a_sidecar_may_not_be_another_output(tmp_path, monkeypatch):
    forbid(monkeypatch, "railhunt:simulate")
    csv = tmp_path / "run.csv"
    assert_input_error(run("simulate", "--speed", "300", "--csv", str(csv), "--png",
                           str(tmp_path / "run.csv.meta.json")), "both name")  # fmt: skip


@pytest.mark.parametrize(("args", "target"), STUDY_WRITERS, ids=lambda v: " ".join(v)
                         if isinstance(v, list) else None)  # fmt: skip
def test_a_study_description_left_from_an_earlier_study_is_kept(tmp_path, monkeypatch, args,
                                                                target):  # fmt: skip
    out = tmp_path / "study.csv"
    side = tmp_path / "study.csv.sweep.json"
    side.write_text("keep me")
    forbid(monkeypatch, target)
    assert_input_error(run(*_args(args, out, tmp_path)), "--out", str(side), "--resume",
                       "--overwrite")  # fmt: skip
    assert side.read_text() == "keep me"


@pytest.mark.parametrize("args", [
    ["reproduce", "--quick", "--out", ""],
    ["reproduce", "--quick", "--out", "  "],
    ["simulate", "--speed", "300", "--csv", ""],
    ["sweep", "C_d1", "--from", "1e5", "--to", "2e5", "--out", ""],
    ["contact", "--png", ""],
    ["plot", "x.csv", "--out", ""],
])  # fmt: skip
def test_an_empty_output_name_is_refused(tmp_path, monkeypatch, args):
    monkeypatch.chdir(tmp_path)
    forbid(monkeypatch, "railhunt:reproduce", "railhunt:simulate", "railhunt:sweep")
    flag = args[-2]
    assert_input_error(run(*args), flag, "empty name")
    assert list(tmp_path.iterdir()) == []


def test_to_toml_keeps_an_existing_file_unless_told(tmp_path):
    path = tmp_path / "mine.toml"
    path.write_text("keep me")
    with pytest.raises(FileExistsError, match="overwrite=True"):
        PAPER.to_toml(path)
    assert path.read_text() == "keep me"
    PAPER.to_toml(path, overwrite=True)
    assert railhunt.load_vehicle(path) == PAPER
