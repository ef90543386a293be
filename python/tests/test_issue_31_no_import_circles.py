"""No circles in the import graph of any crate's modules (scripts/import_graph.py), and the script finds
a circle where there is one: `crate::` paths, `super::` paths, `use` groups and the crate root's
re-exports all count."""

import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "scripts" / "import_graph.py"


def graph(crate, *flags):
    return subprocess.run([sys.executable, str(SCRIPT), str(crate), *flags], capture_output=True, text=True)


def test_no_crate_of_the_workspace_has_a_circle():
    for crate in sorted((ROOT / "crates").iterdir()):
        result = graph(crate, "--check")
        assert result.returncode == 0, result.stdout + result.stderr
        assert "no circle" in result.stdout


def write(crate, files):
    for name, text in files.items():
        path = crate / "src" / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)


def test_a_circle_through_a_root_re_export_and_a_use_group_is_found(tmp_path):
    write(tmp_path, {
        "lib.rs": "mod a;\nmod b;\npub mod c;\npub use a::Alpha;\n",
        "a.rs": "use crate::{b::Beta, c};\npub struct Alpha;\n",
        "b.rs": "pub struct Beta(crate::Alpha);\n",
        "c/mod.rs": "mod d;\n",
        "c/d.rs": "use super::super::b::Beta; // doc: crate::a::Alpha\n#[cfg(test)]\nmod tests { use crate::a::Alpha; }\n",
    })
    result = graph(tmp_path, "--check")
    assert result.returncode == 1
    assert result.stdout.startswith("a ↔ b ")
    assert "c" not in result.stdout.split("(")[0]  # c::d reaches b, but nothing leads back to c

    write(tmp_path, {"b.rs": "pub struct Beta;\n"})
    assert graph(tmp_path, "--check").returncode == 0
