"""The console command lists its jobs and turns suite errors into one clear line and exit code 2."""
import os
import sys
import types

from contact.errors import InputError
from reports import cli


def test_help_lists_every_registered_job(capsys):
    assert cli.main(["--help"]) == 0
    out = capsys.readouterr().out
    for job in cli.JOBS:
        assert f"  {job} " in out


def test_unknown_job_is_refused(capsys):
    assert cli.main(["no-such-job"]) == 2
    assert "ringcontact: error: job = 'no-such-job': unknown" in capsys.readouterr().err


def test_suite_error_escaping_a_job_becomes_exit_code_2(monkeypatch, capsys):
    fake = types.ModuleType("fake_job")

    def main(argv):
        raise InputError("clearance_m = -5e-05 m: must be > 0")

    fake.main = main
    monkeypatch.setitem(sys.modules, "fake_job", fake)
    monkeypatch.setitem(cli.JOBS, "fake", ("fake_job", "a job that fails"))
    assert cli.main(["fake"]) == 2
    err = capsys.readouterr().err
    assert err == "ringcontact fake: error: clearance_m = -5e-05 m: must be > 0\n"


def test_rotor_jobs_start_with_one_blas_thread(monkeypatch):
    """The rotor jobs' small dense algebra runs with one BLAS thread (reports/cli/__init__.py, ONE_BLAS_THREAD: a
    55 × 53 SVD took 104 ms with two OpenBLAS threads on the loaded 2-core machine, 0.28 ms with one); a value the
    user set is kept, and the FEM and study jobs choose their own."""
    from contact.threads import THREAD_VARIABLES

    for k in THREAD_VARIABLES:
        monkeypatch.delenv(k, raising=False)
    assert cli.blas_threads("branch") == {k: "1" for k in THREAD_VARIABLES}
    monkeypatch.setenv("OPENBLAS_NUM_THREADS", "3")
    assert cli.blas_threads("orbit")["OPENBLAS_NUM_THREADS"] == "3"
    for k in THREAD_VARIABLES:
        monkeypatch.delenv(k, raising=False)
    assert cli.blas_threads("fem3d") == {} and cli.blas_threads("study") == {}
    assert all(k not in os.environ for k in THREAD_VARIABLES)
