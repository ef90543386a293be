"""Every code block of README.md and of the guide under docs/ is executed, so that none can rot.

A page's fenced blocks are taken in order, in a temporary working directory of the page's own in which
`examples/` is the repository's (so `examples/...` resolves and `out/...` lands in the temporary directory):

- ```python: executed in one namespace per page (a later block sees an earlier block's names);
- ```console: each line that starts with `$ ` is a command (the other lines are its output, not compared);
  ```sh / ```bash / ```shell: every line is a command (comments and `\\` continuations allowed).
  A command is `ddirac ...`, `cargo run [--release] [-q|--quiet] -p ddirac-cli -- ...` (both run the built
  binary `target/release/ddirac`, or `$DDIRAC_BIN`) or `python ...` (this interpreter); it must exit 0;
- ```toml: a complete spec, checked with `ddirac check` (it must exit 0);
- ```text, ```csv, ```json: output, data or prose, not run.

A marker on the line before a block (blank lines between are allowed) changes that:

- `<!-- not run: REASON -->`: the block is not run (the test command itself, `pip install .`, a Slurm
  submission); the reason is required;
- `<!-- excerpt: PATH -->`: the block's non-blank lines must appear, in order, in the repository's file PATH
  (Rust doc comments' `//!` and `///`, and TOML comments, taken off), which is tested elsewhere (a doctest, a shipped example);
- `<!-- exit status: N -->`: the commands of a shell block must exit N instead of 0.

A block in a language the harness does not know, or in an executable language with a command it cannot
run and no marker, fails the page's test. `python test_docs.py` lists the blocks of every page and what is
done with each, without running them.
"""

import os
import re
import shlex
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import pytest

from command_line import binary

REPO = Path(__file__).resolve().parents[2]
EXECUTABLE = {"python", "console", "sh", "bash", "shell", "toml", "rust"}
NOT_CODE = {"text", "csv", "json"}
SHELL = {"console", "sh", "bash", "shell"}
MARKER = re.compile(r"^<!--\s*(not run|excerpt|exit status)\s*:\s*(.*?)\s*-->$")
FENCE = re.compile(r"^(\s*)(```+|~~~+)\s*([\w+-]*)\s*$")


def pages():
    """README.md, then every Markdown page of the guide."""
    return [REPO / "README.md"] + sorted((REPO / "docs").rglob("*.md"))


def page_id(page):
    return str(page.relative_to(REPO))


@dataclass
class Block:
    page: Path
    line: int  # 1-based line of the opening fence
    language: str
    text: str
    marker: tuple = None  # (kind, argument)

    @property
    def where(self):
        return f"{page_id(self.page)}:{self.line}"

    def disposition(self):
        """What the harness does with the block: 'run', 'excerpt', 'not run', 'not code', or an error."""
        if self.language in NOT_CODE:
            return "not code"
        if self.language not in EXECUTABLE:
            return f"error: a block of unknown language {self.language or '(none)'!r}; label it (text if not code)"
        kind = self.marker[0] if self.marker else None
        if kind == "not run":
            return "not run" if self.marker[1] else "error: `not run` needs a reason"
        if kind == "excerpt":
            return "excerpt"
        if self.language == "rust":
            return "error: a Rust block must be an excerpt of a doctest (`<!-- excerpt: PATH -->`) or marked not run"
        if self.language in SHELL:
            for command in shell_commands(self):
                if isinstance(to_argv(command), str):
                    return f"error: {to_argv(command)}: mark the block `<!-- not run: REASON -->` or change it"
        return "run"


def blocks(page):
    """The fenced code blocks of a Markdown page, with the marker on the line before each."""
    lines = page.read_text(encoding="utf-8").splitlines()
    found, marker, i = [], None, 0
    while i < len(lines):
        stripped = lines[i].strip()
        m = FENCE.match(lines[i])
        if m:
            indent, fence, language = len(m.group(1)), m.group(2), m.group(3).lower()
            body, j = [], i + 1
            while j < len(lines) and not (lines[j].strip().startswith(fence) and lines[j].strip().strip(fence[0]) == ""):
                body.append(lines[j][indent:] if lines[j][:indent].strip() == "" else lines[j].lstrip())
                j += 1
            found.append(Block(page, i + 1, language, "\n".join(body) + "\n", marker))
            marker, i = None, j + 1
            continue
        mm = MARKER.match(stripped)
        if mm:
            marker = (mm.group(1), mm.group(2))
        elif stripped:
            marker = None
        i += 1
    return found


def shell_commands(block):
    """The commands of a shell block: `$ ` lines of a console block, every line of an sh block."""
    commands, current = [], None
    for raw in block.text.splitlines():
        line = raw.rstrip()
        if current is None:
            if block.language == "console":
                if not line.startswith("$ "):
                    continue
                line = line[2:]
            elif not line.strip() or line.lstrip().startswith("#"):
                continue
            current = ""
        if line.endswith("\\"):
            current += line[:-1] + " "
            continue
        commands.append(current + line)
        current = None
    if current:
        commands.append(current)
    return commands


def to_argv(command):
    """The argument vector a documented command runs as, or the reason it cannot be run."""
    if re.search(r"[|&;<>`]|\$\(", command.split("#")[0]):
        return f"`{command}` uses the shell (pipes, redirections, `&&`), which the harness does not run"
    try:
        words = shlex.split(command, comments=True)
    except ValueError as e:
        return f"`{command}` does not parse: {e}"
    if not words:
        return "an empty command"
    if words[0] == "ddirac":
        return [str(binary())] + words[1:]
    if words[:2] == ["cargo", "run"] and "--" in words:
        cut = words.index("--")
        options = words[2:cut]
        allowed = {"--release", "-q", "--quiet", "-p", "ddirac-cli", "--package"}
        if "ddirac-cli" in options and set(options) <= allowed and "--release" in options:
            return [str(binary())] + words[cut + 1:]
        return f"`{command}` builds something else than the release binary of ddirac-cli"
    if words[0] in ("python", "python3"):
        return [sys.executable] + words[1:]
    return f"`{command}` is not a command of ddirac or Python"


def normalized(line, path):
    """A line as an excerpt compares it: stripped; a Rust doc comment's `//!` or `///` taken off; a TOML
    line's trailing comment taken off (a spec's comments may differ between the page and the file)."""
    s = line.strip()
    for prefix in ("//! ", "/// ", "//!", "///"):
        if s.startswith(prefix):
            s = s[len(prefix):]
            break
    if str(path).endswith(".toml"):
        s = re.sub(r"(^|\s)#.*$", "", s)
    return s.strip()


def file_lines(path):
    return [normalized(line, path) for line in (REPO / path).read_text(encoding="utf-8").splitlines()]


def check_excerpt(block):
    path = block.marker[1]
    if not (REPO / path).is_file():
        raise AssertionError(f"{block.where}: the excerpt's file {path} does not exist")
    haystack, at = file_lines(path), 0
    for line in block.text.splitlines():
        s = normalized(line, path)
        if not s:
            continue
        try:
            at = haystack.index(s, at) + 1
        except ValueError:
            raise AssertionError(f"{block.where}: the line {s!r} is not in {path} (in this order)") from None


def run_commands(block, cwd, env):
    expected = int(block.marker[1]) if block.marker and block.marker[0] == "exit status" else 0
    for command in shell_commands(block):
        argv = to_argv(command)
        done = subprocess.run(argv, cwd=cwd, env=env, capture_output=True, text=True, timeout=300)
        if done.returncode != expected:
            raise AssertionError(
                f"{block.where}: `{command}` exited {done.returncode} (expected {expected})\n"
                f"stdout:\n{done.stdout[-3000:]}\nstderr:\n{done.stderr[-3000:]}"
            )


def check_spec(block, cwd, env):
    spec = Path(cwd) / f"block-{block.line}.toml"
    spec.write_text(block.text, encoding="utf-8")
    done = subprocess.run([str(binary()), "check", str(spec)], cwd=cwd, env=env, capture_output=True, text=True,
                          timeout=300)
    if done.returncode != 0:
        raise AssertionError(f"{block.where}: `ddirac check` of the spec exited {done.returncode}\n"
                             f"{done.stdout[-3000:]}\n{done.stderr[-3000:]}")


def run_python(block, namespace):
    code = compile(block.text, f"{block.where} (python block)", "exec")
    exec(code, namespace)  # noqa: S102 -- the documentation's own snippets


@pytest.mark.parametrize("page", pages(), ids=page_id)
def test_every_block_of_the_page_runs(page, tmp_path, monkeypatch):
    page_blocks = blocks(page)
    errors = [f"{b.where}: {b.disposition()[7:]}" for b in page_blocks if b.disposition().startswith("error")]
    assert not errors, "\n".join(errors)
    if any(b.disposition() == "run" and b.language != "python" for b in page_blocks):
        assert binary().is_file(), f"{binary()} is missing: cargo build --release -p ddirac-cli"
    (tmp_path / "examples").symlink_to(REPO / "examples", target_is_directory=True)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    env = dict(os.environ, MPLBACKEND="Agg")
    namespace = {"__name__": "__docs__"}
    for block in page_blocks:
        what = block.disposition()
        if what == "excerpt":
            check_excerpt(block)
        elif what != "run":
            continue
        elif block.language == "python":
            try:
                run_python(block, namespace)
            except Exception as e:
                raise AssertionError(f"{block.where}: the Python block raised {type(e).__name__}: {e}") from e
        elif block.language in SHELL:
            run_commands(block, tmp_path, env)
        elif block.language == "toml":
            check_spec(block, tmp_path, env)


def inventory():
    """Per page: how many blocks are run, checked as excerpts, marked not run, and not code."""
    table = {}
    for page in pages():
        counts = {"run": 0, "excerpt": 0, "not run": 0, "not code": 0, "error": 0}
        for b in blocks(page):
            what = b.disposition()
            counts["error" if what.startswith("error") else what] += 1
        table[page_id(page)] = counts
    return table


def test_every_block_in_an_executable_language_is_run_or_marked():
    table = inventory()
    total = sum(c["run"] + c["excerpt"] for c in table.values())
    assert total > 0
    assert all(c["error"] == 0 for c in table.values()), table


def test_the_readme_is_a_landing_page_with_the_commands_ci_runs():
    readme = (REPO / "README.md").read_text(encoding="utf-8")
    assert len(readme.splitlines()) <= 250
    for command in ("scripts/test.sh", "cargo run --release -p ddirac-cli -- run examples/double_spherical_pendulum.toml"):
        assert command in readme, command


@pytest.mark.parametrize("page", ["README.md", "docs/getting-started.md"])
def test_the_cost_of_each_build_is_stated_before_its_command(page):
    """A reader learns what a build costs before running it: the paragraph before the block of each
    command that compiles names the time it takes, and `pip install -v .` is suggested to see progress."""
    path = REPO / page
    lines = path.read_text(encoding="utf-8").splitlines()
    compiling = ("cargo run --release -p ddirac-cli", "scripts/test.sh", "pip install -v .")
    seen = set()
    for block in blocks(path):
        if block.language not in SHELL:
            continue
        for command in compiling:
            if any(c.strip().startswith(command) for c in block.text.splitlines()):
                before = " ".join(lines[max(0, block.line - 9):block.line - 1])
                assert "minute" in before, f"{page}:{block.line}: no cost stated before `{command}`"
                seen.add(command)
    assert seen == set(compiling), seen


def test_the_python_api_reference_is_current():
    sys.path.insert(0, str(REPO / "scripts"))
    try:
        import python_api_reference
    finally:
        sys.path.pop(0)
    committed = (REPO / "docs" / "reference" / "python-api.md").read_text(encoding="utf-8")
    assert python_api_reference.render() == committed, (
        "docs/reference/python-api.md is not current: run `python scripts/python_api_reference.py`"
    )


def test_the_guide_builds_offline_with_mkdocs_strict(tmp_path):
    pytest.importorskip("mkdocs", reason="mkdocs is not installed (scripts/test.sh installs it)")
    done = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(tmp_path / "site")],
                          cwd=REPO, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr


if __name__ == "__main__":
    width = max(len(p) for p in inventory())
    print(f"{'page':<{width}}  run  excerpt  not-run  not-code  error")
    for page, c in inventory().items():
        print(f"{page:<{width}}  {c['run']:>3}  {c['excerpt']:>7}  {c['not run']:>7}  {c['not code']:>8}  {c['error']:>5}")


def test_the_harness_refuses_blocks_it_would_silently_skip(tmp_path):
    page = tmp_path / "page.md"
    page.write_text(
        "```sh\npip install .\n```\n\n"
        "<!-- not run: it installs -->\n```sh\npip install .\n```\n\n"
        "```\nno language\n```\n\n"
        "```rust\nfn main() {}\n```\n\n"
        "```console\n$ ddirac systems\nsome output\n```\n\n"
        "```sh\ncargo run --release -p ddirac-cli --features dop853 -- bench\n```\n\n"
        "```text\n$ anything\n```\n",
        encoding="utf-8",
    )
    found = [b.disposition().split(":")[0] for b in blocks(page)]
    assert found == ["error", "not run", "error", "error", "run", "error", "not code"]
    assert shell_commands(blocks(page)[4]) == ["ddirac systems"]
