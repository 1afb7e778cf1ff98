"""The progress line (sweep.Progress): count, rate, time left on a terminal, quiet otherwise."""
import io

from sweep import Progress


class _FakeTTY(io.StringIO):
    def isatty(self):
        return True


def test_progress_quiet_when_piped_or_under_ci(monkeypatch):
    monkeypatch.delenv("CI", raising=False)
    piped = io.StringIO()
    p = Progress(3, stream=piped)
    p.update()
    p.close()
    assert piped.getvalue() == ""
    tty = _FakeTTY()
    p = Progress(3, stream=tty)
    p.update(note="x1")
    assert "1/3" in tty.getvalue() and "pt/s" in tty.getvalue()
    monkeypatch.setenv("CI", "true")
    tty2 = _FakeTTY()
    p = Progress(3, stream=tty2)
    p.update()
    assert tty2.getvalue() == ""



def test_progress_counts_to_the_end_and_closes_the_line():
    tty = _FakeTTY()
    with Progress(2, label="fem3d sweep", stream=tty, enabled=True) as p:
        p.update(note="a")
        p.update(note="b")
    out = tty.getvalue()
    assert out.startswith("\rfem3d sweep: 1/2") and "2/2" in out and "0m00s left" in out
    assert out.endswith("\n") and p.done == 2
