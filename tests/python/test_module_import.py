"""The compiled module stands alone: importing and using ``octoreach._core`` never imports the Python
package (no hidden import cycle; progress bars are a factory the package registers)."""
from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

import octoreach


def test_core_imports_and_builds_without_the_python_package():
    package_dir = Path(octoreach.__file__).parent
    core = next(package_dir.glob("_core*.so"))
    urdf = package_dir / "urdf" / "test_arm.urdf"
    script = textwrap.dedent(f"""
        import importlib.abc, importlib.util, sys
        class Forbid(importlib.abc.MetaPathFinder):
            def find_spec(self, name, path=None, target=None):
                if name == "octoreach" or name.startswith("octoreach."):
                    raise ImportError("the compiled module imported " + name)
                return None
        sys.meta_path.insert(0, Forbid())
        sys.path = [p for p in sys.path if p not in ("", ".")]
        spec = importlib.util.spec_from_file_location("_core", {str(core)!r})
        core = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(core)
        robot = core.Robot.from_urdf({str(urdf)!r})
        chain = robot.chain("base_link", "tool0")
        calls = []
        cap = core.CapabilityMap.build(chain, resolution=0.3, directions=12, progress=lambda d, t: calls.append(d))
        cap = core.CapabilityMap.build(chain, resolution=0.3, directions=12, progress=True)
        assert calls, "a callable progress is called without the package"
        assert not any(m == "octoreach" or m.startswith("octoreach.") for m in sys.modules), sorted(sys.modules)
        print("ok", cap.voxel_count if hasattr(cap, "voxel_count") else "")
    """)
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, cwd="/", timeout=300)
    assert out.returncode == 0, out.stderr
    assert out.stdout.startswith("ok")


def test_import_octoreach_loads_neither_matplotlib_nor_the_optional_subpackages():
    script = textwrap.dedent("""
        import sys
        import octoreach
        heavy = [m for m in sys.modules if m.split(".")[0] in ("matplotlib", "viser", "ray", "unified_planning")
                 or m.startswith(("octoreach.exploration", "octoreach.viewer", "octoreach.planning",
                                  "octoreach.cluster", "octoreach.plots", "octoreach.testing", "octoreach.jobs"))]
        assert not heavy, heavy
        # they load on first use
        assert callable(octoreach.explore) and "octoreach.exploration" in sys.modules
        assert callable(octoreach.testing.observable_cells)
        print("ok")
    """)
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, cwd="/", timeout=300)
    assert out.returncode == 0, out.stderr
    assert out.stdout.startswith("ok")
