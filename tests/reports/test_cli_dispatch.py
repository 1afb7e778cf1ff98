"""The console command lists its jobs and turns suite errors into one clear line and exit code 2."""
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
