"""The package as installed (cmake --install, component python) imports in the interpreter it was
built for, outside the build tree, and its example registers two real frames."""
import os
import re
import subprocess
import sys

import pytest

import gasp

EXAMPLE = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                       "python", "examples", "register_tum_pair.py")


@pytest.fixture(scope="module")
def installed(build_dir, tmp_path_factory):
    prefix = tmp_path_factory.mktemp("prefix")
    subprocess.run(["cmake", "--install", build_dir, "--component", "python", "--prefix", str(prefix)],
                   check=True, stdout=subprocess.DEVNULL)
    found = [root for root, _, files in os.walk(prefix) if "__init__.py" in files and os.path.basename(root) == "gasp"]
    assert len(found) == 1, found
    assert re.search(r"lib/python3(\.\d+)?/(dist|site)-packages/gasp$", found[0]), found[0]
    return prefix, os.path.dirname(found[0])


def run_installed(installed, args, cwd):
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONPATH"] = installed[1]
    return subprocess.run([sys.executable, *args], cwd=cwd, env=env, capture_output=True, text=True, timeout=600)


def test_the_installed_package_imports_outside_the_build(installed, tmp_path):
    r = run_installed(installed, ["-c", "import gasp, os; print(os.path.dirname(gasp.__file__)); "
                                        "print(len(gasp.default_params()['segment']))"], tmp_path)
    assert r.returncode == 0, r.stderr
    where, keys = r.stdout.split()
    assert where == os.path.join(installed[1], "gasp") and int(keys) == len(gasp.default_params()["segment"])
    assert os.path.isfile(os.path.join(installed[0], "share", "gasp", "examples", "register_tum_pair.py"))


def test_the_example_registers_two_real_frames_and_prints_the_error(installed, fr1_xyz, tmp_path):
    example = os.path.join(installed[0], "share", "gasp", "examples", "register_tum_pair.py")
    r = run_installed(installed, [example, fr1_xyz], tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    m = re.search(r"pose error: ([0-9.]+) cm, ([0-9.]+) deg", r.stdout)
    assert m, r.stdout
    assert float(m.group(1)) < 3.0 and float(m.group(2)) < 2.0


def test_the_example_explains_its_usage(tmp_path):
    r = subprocess.run([sys.executable, EXAMPLE], capture_output=True, text=True, cwd=tmp_path)
    assert r.returncode == 2 and "register_tum_pair.py" in r.stderr
