"""Size limits of the code (scripts/check_sizes.py): no file or function over its limit but the named allow-list,
and the C++ brace scanner measures what a reader would call a function."""
from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parents[2] / "scripts" / "check_sizes.py"
pytestmark = pytest.mark.skipif(not SCRIPT.is_file(), reason="needs the source tree (scripts/check_sizes.py)")


@pytest.fixture(scope="module")
def sizes():
    spec = importlib.util.spec_from_file_location("check_sizes", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_no_file_or_function_is_over_its_limit():
    r = subprocess.run([sys.executable, str(SCRIPT)], capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    for kind in ("cpp file", "cpp function", "python module", "python function"):
        assert f"largest {kind}:" in r.stdout


def test_the_scanner_skips_comments_strings_and_preprocessor_lines(sizes):
    text = '''#include <string>
#define BRACE {
namespace a {
// a comment with a brace {
/* a block comment { { */
int f(int x) {
  const char* s = "}}} \\" {";
  char c = '{';
  auto r = R"raw(}{)raw";
  int big = 1'000'000;
  if (x) {
    return [] { return 1; }();
  }
  return x;
}
}  // namespace a
'''
    assert sizes.cpp_functions(text) == [("f", 6, 10)]


def test_the_scanner_finds_methods_constructors_and_templates(sizes):
    text = '''struct S : Base {
 public:
  S(int a) : a_(a), b_{a} {
    a_ += 1;
  }
  template <class T>
  T get() const noexcept { return T(a_); }
  static constexpr int k[] = {1, 2};
  int a_, b_;
};
const int table[] = {1, 2, 3};
auto S::size() const -> std::size_t {
  return 0;
}
PYBIND11_MODULE(_core, m) {
  m.def("f", [](int x) {
    return x;
  });
}
'''
    assert sizes.cpp_functions(text) == [("S", 3, 3), ("get", 7, 1), ("S::size", 12, 3), ("PYBIND11_MODULE", 15, 5)]


def test_over_the_limit_is_reported_and_fails(sizes, tmp_path):
    (tmp_path / "cpp" / "src").mkdir(parents=True)
    (tmp_path / "bindings").mkdir()
    (tmp_path / "python" / "octoreach").mkdir(parents=True)
    body = "\n".join(f"  x += {i};" for i in range(130))
    (tmp_path / "cpp" / "src" / "long.cpp").write_text(f"void long_one(int x) {{\n{body}\n}}\n")
    (tmp_path / "python" / "octoreach" / "m.py").write_text("def f():\n" + "    pass\n" * 90)
    rows = {(k, f, n): lines for k, f, n, _, lines in sizes.measure(tmp_path)}
    assert rows[("cpp function", "cpp/src/long.cpp", "long_one")] == 132
    assert rows[("python function", "python/octoreach/m.py", "f")] == 91
    r = subprocess.run([sys.executable, str(SCRIPT), str(tmp_path)], capture_output=True, text=True)
    assert r.returncode == 1 and "OVER THE LIMIT" in r.stdout and "long_one" in r.stdout and "m.py" in r.stdout
