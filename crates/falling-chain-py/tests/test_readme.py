"""The README's Python, as a newcomer runs it: its install command is the
one `.ci/run` installs this module with (in a fresh virtual environment),
and its lines run in order, as written, from the root of a fresh copy of
the checkout (its tracked files, in a temporary directory). The README's
shell commands run in `tests/cli/readme.rs`."""

import os
import shutil
import subprocess

from conftest import ROOT

README = ROOT / "README.md"


def block_after(heading, fence):
    text = README.read_text()
    after = text.split(f"\n{heading}\n", 1)[1]
    lines = after.splitlines()
    start = next(i for i, l in enumerate(lines) if l.startswith(fence))
    end = next(i for i in range(start + 1, len(lines)) if lines[i].startswith("```"))
    return lines[start + 1:end], after


def test_the_readmes_install_command_is_the_one_ci_runs():
    _, after = block_after("## Python", "```python")
    install = next(l.strip() for l in after.splitlines() if l.strip().startswith("pip install"))
    assert install == "pip install ./crates/falling-chain-py"
    ci = (ROOT / ".ci" / "run").read_text()
    assert "-m pip install ./crates/falling-chain-py" in ci


def test_the_readmes_python_lines_run_on_a_fresh_copy(tmp_path, monkeypatch):
    code, _ = block_after("## Python", "```python")
    assert 3 <= len(code) <= 5, code
    listed = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, check=True)
    for name in filter(None, listed.stdout.decode().split("\0")):
        src = ROOT / name
        if src.is_file():
            dst = tmp_path / name
            dst.parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(src, dst)
    monkeypatch.chdir(tmp_path)
    namespace = {"__name__": "__main__"}
    exec(compile("\n".join(code), "README.md", "exec"), namespace)
    run, vmax = namespace["run"], namespace["vmax"]
    assert run.status == "ok" and run.links == 100
    assert len(vmax) == 120 and (vmax > 0).all()
    assert os.getcwd() == str(tmp_path)
