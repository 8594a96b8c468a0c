"""What a new user's trial found (issue 13), from the shell: output paths checked before
any computation, one overwrite policy, refusals with the flags that help, long runs
announced, verdicts apart from solver status, the metadata every output carries, and
clear messages."""

from __future__ import annotations

import hashlib
import json
import socket
import threading
from pathlib import Path

import numpy as np
import pytest

import railhunt
from test_cli import assert_input_error, run

PAPER = railhunt.Vehicle.paper2019()


class Computed(Exception):
    """Raised by a computation that must not start."""


def forbid(monkeypatch, *targets: str) -> None:
    """Make the computations at ``targets`` ("module:attribute") raise :class:`Computed`
    (and let it through the command line's safety net, which would make it one line)."""
    import importlib

    monkeypatch.setenv("RAILHUNT_DEBUG", "1")
    def refuse(*args, **kwargs):
        raise Computed("computed before the outputs were checked")

    for target in targets:
        module, name = target.split(":")
        monkeypatch.setattr(importlib.import_module(module), name, refuse)


def sweep_file(tmp_path: Path) -> Path:
    """A small results file (linear output only), for the commands that read one."""
    out = tmp_path / "lines.csv"
    result = run("sweep", "C_d1", "--from", "1e5", "--to", "3e5", "--num", "2", "--outputs",
                 "linear_critical_speed", "--workers", "1", "--out", str(out))  # fmt: skip
    assert result.exit_code == 0, result.stderr
    return out


#: Every command that writes files: its arguments with FILE standing for one output, and
#: the computation it would start ("module:attribute").
WRITERS = [
    (["simulate", "--speed", "300", "--csv", "FILE"], "railhunt:simulate"),
    (["simulate", "--speed", "300", "--png", "FILE"], "railhunt:simulate"),
    (["curve", "--radius", "3000", "--speed", "300", "--png", "FILE"], "railhunt:curving"),
    (["eigen", "--csv", "FILE"], "railhunt:eigen_analysis"),
    (["eigen", "--png", "FILE"], "railhunt:eigen_analysis"),
    (["bifurcation", "--png", "FILE"], "railhunt:bifurcation_diagram"),
    (["bifurcation", "--fu-family", "3", "--family-png", "FILE"],
     "railhunt:bifurcation_diagram"),
    (["frequency", "--png", "FILE"], "railhunt:hunting_frequency"),
    (["frequency", "--damper-png", "FILE"], "railhunt:hunting_frequency"),
    (["contact", "--png", "FILE"], "railhunt:contact_geometry"),
    (["contact", "--csv", "FILE"], "railhunt:contact_geometry"),
    (["creep", "--png", "FILE"], "railhunt.mechanics.curves:creep_curves"),
    (["creep", "--csv", "FILE"], "railhunt.mechanics.curves:creep_curves"),
    (["spectrogram", "RUN", "--channel", "y_w1", "--png", "FILE"],
     "railhunt.analysis.spectrogram:read_channel"),
    (["sweep", "C_d1", "--from", "1e5", "--to", "2e5", "--out", "FILE"], "railhunt:sweep"),
    (["stability-map", "--radius", "inf", "--png", "FILE"], "railhunt:stability_map"),
    (["stability-map", "--radius", "inf", "--csv", "FILE"], "railhunt:stability_map"),
    (["stability-map", "--radius", "inf", "--out", "FILE"], "railhunt:stability_map"),
    (["sections", "RESULTS", "--png", "FILE"], "railhunt:section_changes"),
    (["sections", "RESULTS", "--csv", "FILE"], "railhunt:section_changes"),
    (["plot", "RESULTS", "--out", "FILE"], "railhunt.studies.sections:sweep_lines"),
]  # fmt: skip


def _args(args: list[str], file: Path, tmp_path: Path) -> list[str]:
    out = []
    for a in args:
        if a == "FILE":
            out.append(str(file))
        elif a == "RUN":
            run_csv = tmp_path / "run.csv"
            run_csv.write_text("t [s],y_w1 [m]\n" + "".join(f"{k * 0.01},{np.sin(k)}\n"
                                                           for k in range(600)))  # fmt: skip
            out.append(str(run_csv))
        elif a == "RESULTS":
            out.append(str(sweep_file(tmp_path)))
        else:
            out.append(a)
    return out


def _flag(args: list[str]) -> str:
    return args[args.index("FILE") - 1]


@pytest.mark.parametrize(("args", "target"), WRITERS, ids=lambda v: " ".join(v)
                         if isinstance(v, list) else None)  # fmt: skip
def test_an_output_that_is_a_folder_is_refused_before_computing(tmp_path, monkeypatch, args,
                                                                 target):  # fmt: skip
    # A guard (click's own path check refuses a folder too): before any computation.
    folder = tmp_path / "out.png"
    folder.mkdir()
    argv = _args(args, folder, tmp_path)
    forbid(monkeypatch, target)
    assert_input_error(run(*argv), _flag(args), str(folder))


@pytest.mark.parametrize(("args", "target"), WRITERS, ids=lambda v: " ".join(v)
                         if isinstance(v, list) else None)  # fmt: skip
def test_an_existing_output_is_refused_before_computing(tmp_path, monkeypatch, args, target):
    existing = tmp_path / "old.out"
    existing.write_text("keep me")
    argv = _args(args, existing, tmp_path)
    forbid(monkeypatch, target)
    assert_input_error(run(*argv), _flag(args), "exists", "--overwrite")
    assert existing.read_text() == "keep me"


@pytest.mark.skipif(not Path("/proc/self").is_dir(), reason="needs Linux's /proc")
def test_an_unwritable_folder_is_refused_before_computing(monkeypatch):
    # /proc takes no new files, not even from root (for whom permission bits do not count).
    forbid(monkeypatch, "railhunt:bifurcation_diagram")
    assert_input_error(run("bifurcation", "--png", "/proc/railhunt-figure.png"), "--png",
                       "cannot write", "/proc")  # fmt: skip


def test_overwrite_replaces_an_existing_file(tmp_path):
    csv = tmp_path / "run.csv"
    csv.write_text("old")
    result = run("simulate", "--speed", "250", "--duration", "0.5", "--csv", str(csv),
                 "--overwrite")  # fmt: skip
    assert result.exit_code == 0, result.stderr
    assert csv.read_text().startswith("t [s],")


def test_two_outputs_may_not_name_the_same_file(tmp_path, monkeypatch):
    forbid(monkeypatch, "railhunt:simulate")
    same = str(tmp_path / "x.out")
    assert_input_error(run("simulate", "--speed", "300", "--csv", same, "--png", same),
                       "--csv", "--png", "both")


def test_reproduce_keeps_an_earlier_report_without_overwrite(tmp_path, monkeypatch):
    (tmp_path / "report.html").write_text("earlier")
    forbid(monkeypatch, "railhunt:reproduce")
    assert_input_error(run("reproduce", "--out", str(tmp_path), "--quick"), "--out",
                       "report.html", "--overwrite")  # fmt: skip
    assert (tmp_path / "report.html").read_text() == "earlier"


def test_the_overwrite_policy_is_in_the_help():
    text = " ".join(run("--help").stdout.split())
    assert "not replaced" in text and "--overwrite" in text
    for command in ("simulate", "eigen", "bifurcation", "contact", "creep", "spectrogram", "plot",
                    "sections", "reproduce", "curve", "frequency", "sweep", "stability-map"):
        assert "--overwrite" in run(command, "--help").stdout, command


# --------------------------------------------------------------------------- refusals


def test_histories_that_do_not_fit_in_memory_are_refused():
    # 1e8 rows of 75 channels: 60 GB at least, on any machine railhunt runs on.
    line = assert_input_error(run("simulate", "--speed", "330", "--duration", "100000"),
                              "--duration 100000", "GB", "--output-dt")  # fmt: skip
    assert "1e+08 rows" in line


@pytest.mark.parametrize("command", [
    ["simulate", "--speed", "300", "--duration", "0.5"],
    ["critical-speed"],
    ["frequency", "--from", "300", "--to", "300"],
    ["bifurcation"],
])  # fmt: skip
def test_a_stiff_yaw_damper_is_refused_up_front(command):
    # K_d / C_d1 = 1e7 1/s: the automatic step would be 0.6 / 1e7 = 6e-8 s.
    line = assert_input_error(run(*command, "--set", "C_d1=1"), "C_d1", "K_d", "6e-08 s")
    assert "C_d1 >= 167 N*s/m" in line  # 1e7 N/m * 1e-3 s / (100 * 0.6)


def test_a_long_run_is_announced_before_it_starts(monkeypatch):
    forbid(monkeypatch, "railhunt:simulate")
    result = run("simulate", "--speed", "300", "--duration", "30000", "--output-dt", "1")
    assert isinstance(result.exception, Computed)
    # 3e7 steps of 1 ms at 2.5 us: 75 s, said before the run.
    assert "railhunt: note: this will take about 75 s (3e+07 RK4 steps of 0.001 s" in \
        result.stderr  # fmt: skip


def test_a_fine_contact_table_is_announced(monkeypatch):
    forbid(monkeypatch, "railhunt:contact_geometry")
    result = run("contact", "--step", "0.0015", "--y-max", "30")
    assert isinstance(result.exception, Computed)
    # 40001 positions at 2.1 ms each (measured: 2401 in 5.0 s).
    assert "railhunt: note: this will take about 84 s (4e+04 contact positions" in result.stderr


def test_a_short_run_is_not_announced():
    result = run("simulate", "--speed", "250", "--duration", "1")
    assert result.exit_code == 0 and "note:" not in result.stderr


def test_a_search_that_may_be_long_says_up_to(monkeypatch):
    # C_d1 = 300 N*s/m: step 0.6 * 300 / 1e7 = 1.8e-5 s; every trial at most 60 s.
    forbid(monkeypatch, "railhunt:critical_speed")
    result = run("critical-speed", "--set", "C_d1=300")
    assert isinstance(result.exception, Computed)
    assert "railhunt: note: this will take about" in result.stderr
    assert "up to" in result.stderr and "1.8e-05 s" in result.stderr


# --------------------------------------------------------------------------- verdicts


def test_simulate_shows_the_verdict_apart_from_the_solver_status(tmp_path, monkeypatch):
    titles = []
    import railhunt.plots

    monkeypatch.setattr(railhunt.plots, "plot_time_history",
                        lambda result, path, **kw: titles.append(kw.get("verdict")))
    hunting = run("simulate", "--speed", "350", "--png", str(tmp_path / "a.png")).stdout
    assert "status:     solver ok (reached t = 10.000 s)" in hunting
    # The stable cycle at 350 km/h has 9.625 mm (shooting, docs/bifurcation.md); after 10 s
    # the run is within 0.1 mm of it.
    amplitude = float(hunting.split("verdict:    hunting: limit cycle of ")[1].split(" mm")[0])
    assert amplitude == pytest.approx(9.625, abs=0.1)
    decays = run("simulate", "--speed", "250", "--png", str(tmp_path / "b.png")).stdout
    assert "verdict:    stable: the motion died out" in decays  # a verdict word
    assert titles == [f"hunting, {amplitude:.3g} mm", "stable"]


def test_a_tiny_defect_does_not_put_the_critical_speed_above_the_hopf_point():
    result = run("critical-speed", "--amplitude", "0.01", "--json")
    assert result.exit_code == 0, result.stderr
    data = json.loads(result.stdout)
    # Below the Hopf point (441.3 km/h) the centred running is stable; above it a 0.01 mm
    # defect grows: no trial above 441.3 km/h may be judged stable.
    assert data["nonlinear_critical_speed_kmh"] <= data["linear_critical_speed_kmh"]
    assert data["above_linear_critical_speed"] is False
    assert all(t["verdict"] == "hunting" for t in data["trials"]
               if t["speed_kmh"] > data["linear_critical_speed_kmh"])  # fmt: skip


def test_a_critical_speed_above_the_linear_one_is_flagged(monkeypatch):
    class Linear:
        speed_kmh, frequency_hz, is_hunting_mode = 250.0, 3.0, True

    import railhunt

    monkeypatch.setattr(railhunt, "linear_critical_speed", lambda *a, **k: Linear())
    data = json.loads(run("critical-speed", "--json").stdout)
    assert data["nonlinear_critical_speed_kmh"] == 301.0
    assert data["above_linear_critical_speed"] is True
    text = " ".join(run("critical-speed").stdout.split())
    assert "note: the nonlinear critical speed lies above the linear one (250.0 km/h)" in text


def test_the_trial_table_explains_a_steady_cycle():
    text = " ".join(run("critical-speed").stdout.split())
    assert "steady cycle: hunting on a limit cycle: the envelope is stationary" in text
    assert "a small negative growth is still a cycle" in text


# --------------------------------------------------------------------------- metadata


def fingerprint(vehicle) -> str:
    """The parameters' fingerprint, derived here from the definition (docs)."""
    block = {"parameters": vehicle.as_dict(), "contact": repr(vehicle.contact)}
    text = json.dumps(block, sort_keys=True, separators=(",", ":"))
    return "sha256:" + hashlib.sha256(text.encode()).hexdigest()[:16]


def assert_traced(data: dict, vehicle=PAPER, name: str = "paper2019") -> None:
    assert data["railhunt_version"] == railhunt.__version__
    if vehicle is not None:
        assert data["vehicle"] == name
        assert data["vehicle_fingerprint"] == fingerprint(vehicle)


@pytest.mark.parametrize("args", [
    ["critical-speed", "--tol", "5", "--json"],
    ["critical-speed", "--method", "stochastic", "--track-length", "200", "--start", "250",
     "--tol", "10", "--json"],
    ["curve", "--radius", "3000", "--speed", "250", "--json"],
    ["frequency", "--from", "300", "--to", "300", "--json"],
    ["stability-map", "--radius", "inf", "--outputs", "linear_critical_speed", "--workers",
     "1", "--json"],
])  # fmt: skip
def test_every_json_output_is_traced(args):
    result = run(*args)
    assert result.exit_code == 0, result.stderr
    assert_traced(json.loads(result.stdout))


def test_the_fingerprint_follows_the_parameters_not_the_name():
    data = json.loads(run("curve", "--radius", "3000", "--speed", "250", "--set",
                          "C_d1=200e3", "--json").stdout)  # fmt: skip
    changed = PAPER.replace(C_d1=200e3)
    assert_traced(data, changed, "paper2019 with C_d1=200000")
    assert data["vehicle_fingerprint"] != fingerprint(PAPER)
    assert fingerprint(changed.replace(name="another name")) == fingerprint(changed)


def test_every_csv_output_has_a_metadata_sidecar(tmp_path):
    csvs = {
        "simulate": ["simulate", "--speed", "250", "--duration", "0.5", "--csv"],
        "eigen": ["eigen", "--from", "300", "--to", "310", "--csv"],
        "stability-map": ["stability-map", "--radius", "inf", "--outputs",
                          "linear_critical_speed", "--workers", "1", "--csv"],
    }  # fmt: skip
    for name, args in csvs.items():
        csv = tmp_path / f"{name}.csv"
        result = run(*args, str(csv))
        assert result.exit_code == 0, (name, result.stderr)
        meta = json.loads((tmp_path / f"{name}.csv.meta.json").read_text())
        assert_traced(meta)
        assert meta["file"] == csv.name and meta["command"] == f"railhunt {name}"
        header = csv.read_text().splitlines()[0].split(",")
        assert meta.get("columns", header) == header
    contact = tmp_path / "contact.csv"
    assert run("contact", "--csv", str(contact)).exit_code == 0
    meta = json.loads((tmp_path / "contact.csv.meta.json").read_text())
    assert_traced(meta, None)
    assert meta["wheel"] == "S1002"


def test_a_study_sidecar_and_the_sections_carry_the_vehicle(tmp_path):
    results = sweep_file(tmp_path)
    side = json.loads(Path(str(results) + ".sweep.json").read_text())
    assert_traced(side["provenance"])
    assert railhunt.read_results(results).column("C_d1").tolist() == [1e5, 3e5]
    sections = tmp_path / "sections.csv"
    data = json.loads(run("sections", str(results), "--csv", str(sections), "--json").stdout)
    assert_traced(data, None)
    assert_traced(data["source"])
    assert_traced(json.loads((tmp_path / "sections.csv.meta.json").read_text())["source"])


def test_a_renamed_vehicle_still_resumes_its_study(tmp_path):
    out = tmp_path / "s.csv"
    base = ["sweep", "C_d1", "--from", "1e5", "--to", "3e5", "--num", "2", "--outputs",
            "linear_critical_speed", "--workers", "1", "--out", str(out)]  # fmt: skip
    assert run(*base).exit_code == 0
    toml = tmp_path / "renamed.toml"
    toml.write_text('[vehicle]\nbase = "paper2019"\nname = "renamed"\n')
    result = run(*base, "--resume", "--vehicle", str(toml))
    assert result.exit_code == 0, result.stderr


def test_spectrogram_json_names_the_run_it_analyses(tmp_path):
    csv = tmp_path / "run.csv"
    assert run("simulate", "--speed", "350", "--duration", "6", "--csv", str(csv)).exit_code == 0
    data = json.loads(run("spectrogram", str(csv), "--channel", "y_w1", "--json").stdout)
    assert_traced(data, None)
    assert_traced(data["source"])


# --------------------------------------------------------------------------- messages


def test_a_binary_file_is_not_a_csv_record(tmp_path):
    binary = tmp_path / "binary.prw"
    binary.write_bytes(bytes(range(256)) * 8)
    assert_input_error(run("spectrogram", str(binary), "--channel", "y_w1"), str(binary),
                       "not a text CSV file")  # fmt: skip


def test_lhs_without_samples_names_the_flag(tmp_path):
    line = assert_input_error(run("sweep", "C_d1", "--from", "1e5", "--to", "2e5", "--design",
                                  "lhs", "--out", str(tmp_path / "x.csv")), "--samples")
    assert "None" not in line


@pytest.mark.parametrize(("tie", "words"), [
    ("f22=nope", ["'nope' is not a vehicle parameter", "railhunt parameters"]),
    ("f2=f11", ["'f2' is not a vehicle parameter", "did you mean", "f22"]),
])  # fmt: skip
def test_a_tie_to_an_unknown_name_suggests_names(tmp_path, tie, words):
    line = assert_input_error(run("sweep", "f11", "--from", "2e6", "--to", "3e6", "--tie", tie,
                                  "--out", str(tmp_path / "x.csv")), "--tie", *words)
    assert "PARAMETERS" not in line


def test_bifurcation_says_when_the_fold_lies_below_the_range(monkeypatch):
    from railhunt.analysis.branches import BifurcationDiagram

    diagram = BifurcationDiagram([], 441.3, 441.4, 3.98, float("nan"), "subcritical",
                                 (300.0, 350.0), True, "", fold_below_range=True)
    monkeypatch.setattr(railhunt, "bifurcation_diagram", lambda *a, **k: diagram)
    text = " ".join(run("bifurcation", "--from", "300", "--to", "350").stdout.split())
    assert "nonlinear critical speed (lowest limit cycle): below the range" in text
    assert "lower --from" in text


# --------------------------------------------------------------------------- scheduler


@pytest.fixture()
def not_dask():
    """A TCP server that answers like a web server, not a Dask scheduler."""
    server = socket.create_server(("127.0.0.1", 0))
    stop = threading.Event()

    def serve() -> None:
        server.settimeout(0.2)
        while not stop.is_set():
            try:
                conn, _ = server.accept()
            except OSError:
                continue
            with conn:
                conn.sendall(b"HTTP/1.1 400 Bad Request\r\nContent-Length: 0\r\n\r\n")

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    yield f"tcp://127.0.0.1:{server.getsockname()[1]}"
    stop.set()
    thread.join()
    server.close()


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.mark.parametrize("command", [
    ["sweep", "C_d1", "--from", "1e5", "--to", "2e5", "--num", "2", "--outputs",
     "linear_critical_speed"],
    ["stability-map", "--radius", "inf", "--outputs", "linear_critical_speed"],
])  # fmt: skip
def test_a_server_that_is_not_dask_is_named(tmp_path, not_dask, command):
    result = run(*command, "--scheduler", not_dask, "--connect-timeout", "5", "--out",
                 str(tmp_path / "x.csv"))  # fmt: skip
    assert_input_error(result, f"--scheduler {not_dask}", "not a Dask scheduler")


def test_a_refused_port_fails_at_once(tmp_path):
    import time

    address = f"tcp://127.0.0.1:{free_port()}"
    start = time.perf_counter()
    result = run("sweep", "C_d1", "--from", "1e5", "--to", "2e5", "--num", "2", "--outputs",
                 "linear_critical_speed", "--scheduler", address, "--out",
                 str(tmp_path / "x.csv"))  # fmt: skip
    assert_input_error(result, f"--scheduler {address}", "refused")
    assert time.perf_counter() - start < 5.0


def test_reproduce_takes_a_connect_timeout(tmp_path):
    address = f"tcp://127.0.0.1:{free_port()}"
    result = run("reproduce", "--out", str(tmp_path / "r"), "--scheduler", address,
                 "--connect-timeout", "2")  # fmt: skip
    assert_input_error(result, f"--scheduler {address}", "refused")


@pytest.mark.parametrize("value", ["0", "-1", "nan", "1e9"])
def test_a_connect_timeout_out_of_range_is_refused(tmp_path, value):
    result = run("sweep", "C_d1", "--from", "1e5", "--to", "2e5", "--scheduler", "tcp://x:1",
                 "--connect-timeout", value, "--out", str(tmp_path / "x.csv"))  # fmt: skip
    assert_input_error(result, "--connect-timeout")
