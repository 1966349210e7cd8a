# tacta.plugins(): what the loader found and, for every file it refused, why. The broken plugins
# are the loader tests' own (tests/engine/plugin/plugins); ctest passes their folder.
import json
import os
import subprocess
import sys

import pytest
import tacta


def test_the_build_plugins_load_and_none_is_refused():
    found = tacta.plugins()
    kinds = {(p["kind"], p["name"]) for p in found["loaded"]}
    assert {("model", "corotational_fem"), ("device", "mouse"), ("collision", "bvh")} <= kinds
    assert found["refused"] == []
    assert all(isinstance(p, str) for p in found["search_paths"])


def test_refused_plugins_come_with_their_reason():
    broken = os.environ.get("TACTA_TEST_BROKEN_PLUGIN_DIR")
    if not broken:
        pytest.skip("TACTA_TEST_BROKEN_PLUGIN_DIR not set (ctest sets it)")
    # The registry is loaded once a process: a fresh interpreter searches the broken folder too.
    code = "import json, tacta; print(json.dumps(tacta.plugins()))"
    env = dict(os.environ, TACTA_PLUGIN_PATH=broken)
    done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120,
                          check=True)
    found = json.loads(done.stdout)
    assert broken in found["search_paths"]
    reasons = {os.path.basename(r["file"]): r["reason"] for r in found["refused"]}
    assert set(reasons) == {"tacta_test_no_entry.so", "tacta_test_abi_float.so", "tacta_test_missing_step.so",
                            "tacta_test_duplicate_b.so", "tacta_test_absent_dependency.so"}
    assert "tacta_plugin_entry" in reasons["tacta_test_no_entry.so"]
    assert "scalar type (double vs float)" in reasons["tacta_test_abi_float.so"]
    assert "required function 'step'" in reasons["tacta_test_missing_step.so"]
    assert "tacta_test_duplicate_a.so" in reasons["tacta_test_duplicate_b.so"]
    assert "dlopen failed" in reasons["tacta_test_absent_dependency.so"]
    loaded = {(p["kind"], p["name"]) for p in found["loaded"]}
    assert ("model", "test_duplicate") in loaded and ("model", "corotational_fem") in loaded


def test_an_installed_package_loads_the_plugins_it_carries():
    # pip's package holds tacta/plugins beside the module (docs/PYTHON.md); the build tree's has none.
    own = os.path.join(os.path.dirname(os.path.realpath(tacta._tacta.__file__)), "plugins")
    if not os.path.isdir(own):
        pytest.skip("the build tree's module: plugins come from build/lib/tacta/plugins")
    found = tacta.plugins()
    assert os.path.realpath(found["search_paths"][0]) == own
    carried = {f for f in os.listdir(own) if f.endswith(".so")}
    assert {os.path.basename(p["file"]) for p in found["loaded"]} == carried
    assert all(os.path.dirname(os.path.realpath(p["file"])) == own for p in found["loaded"])
