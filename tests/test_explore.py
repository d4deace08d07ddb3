"""The Jupyter explorers (issue 13): built and driven headless, data drawn = the API's numbers."""

from __future__ import annotations

import asyncio
import subprocess
import sys

import numpy as np
import pytest

pytest.importorskip("ipywidgets")

import aliasing  # noqa: E402
from aliasing import budgets, error, explore, faces, geometry, schemes, warping  # noqa: E402
from aliasing import pictures  # noqa: E402
from aliasing.raster.validate import validate  # noqa: E402

PNG = b"\x89PNG"


@pytest.fixture(scope="module")
def ov():
    return explore.overhead()


@pytest.fixture(scope="module")
def dirs():
    return explore.directions(resolution=24)


def test_every_explorer_builds_headless_and_shows_a_picture():
    for make in (explore.overhead, explore.directions, explore.cascades, explore.faces):
        e = make()
        assert e.error is None, e.error
        assert e.data is not None and e.png().startswith(PNG)
        assert e.image in e.children and e.message in e.children


def test_overhead_data_and_drawn_curves_equal_the_api(ov):
    assert ov.set_state({"f_over_n": 100.0, "fov": 90.0, "rule": "lispsm", "res_image": 512})
    d, npr = ov.data, float(warping.n_prime_lispsm(1.0, 100.0))
    assert d["n_prime"] == npr
    assert d["S"] == pytest.approx(49.5, rel=1e-12)  # the same value as aliasing/__init__.py's example (LiSPSM, f/n = 100, fov = 90°)
    assert d["S"] == float(aliasing.storage_factor(1.0, 100.0, 90.0, npr))
    ax_z, ax_eta = ov.figure.axes[:2]
    np.testing.assert_array_equal(ax_z.lines[0].get_ydata(), error.m_x(d["z"], 1.0, 100.0, npr))
    np.testing.assert_array_equal(ax_z.lines[1].get_ydata(), error.m_z(d["z"], 1.0, 100.0, 90.0, npr))
    np_eta = warping.n_prime_from_eta(d["eta_axis"], 1.0, 100.0)
    np.testing.assert_array_equal(ax_eta.lines[2].get_ydata(), error.storage_factor(1.0, 100.0, 90.0, np_eta))
    rs, rt = error.critical_resolution(1.0, 100.0, 90.0, npr, res_image=512)
    assert (d["res_s"], d["res_t"]) == (float(rs), float(rt))


def test_overhead_eta_and_typed_n_prime(ov):
    ov.set_state({"f_over_n": 1000.0, "fov": 60.0, "rule": "eta", "eta": 1.0})
    assert ov.data["n_prime"] == pytest.approx(1.0)  # eq. 11: eta = 1 is PSM, n' = n
    ov.set_state({"rule": "n_prime", "n_prime": "3.5"})
    assert ov.data["n_prime"] == 3.5 and ov.data["M_x"] == float(error.max_error_x(1.0, 1000.0, 3.5))


def test_bad_text_entry_shows_its_message_and_keeps_the_last_good_state(ov):
    ov.set_state({"rule": "n_prime", "n_prime": "2"})
    good, picture = ov.data, ov.png()
    assert not ov.set_state({"n_prime": "two"})
    assert "n′ must be a number" in ov.error and "n′ must be a number" in ov.message.value
    assert ov.data is good and ov.png() == picture
    ov.controls["n_prime"].value = "-1"
    assert "must be > 0" in ov.error and ov.data is good
    ov.controls["n_prime"].value = "4"
    assert ov.error is None and ov.message.value == "" and ov.data["n_prime"] == 4.0


def test_directions_map_and_chosen_direction_equal_evaluate(dirs):
    assert dirs.set_state({"scheme": "zp2+p", "f_over_n": 500.0, "fov": 50.0, "gamma": 45.0, "azimuth": 20.0})
    d = dirs.data
    u, v, light = geometry.hemisphere_map(24)
    inside = np.isfinite(light[..., 0])
    np.testing.assert_array_equal(d["S_map"][inside], schemes.evaluate("ZP2+P", 1.0, 500.0, 50.0, light[inside]).S)
    assert np.isnan(d["S_map"][~inside]).all()
    one = schemes.evaluate("ZP2+P", 1.0, 500.0, 50.0, geometry.light_direction(45.0, 20.0)[None])
    np.testing.assert_array_equal(d["M_x"], one.M_x[0])
    np.testing.assert_array_equal(d["M_z"], one.M_z[0])
    assert d["S"] == float(one.S[0]) and d["scheme"] == "ZP2+P"
    st = schemes.evaluate("ZP2+P", 1.0, 500.0, 50.0, "hemisphere:1024")
    assert (d["S_min"], d["S_max"], d["S_mean"]) == (float(st.S.min()), float(st.S.max()), float(st.S.mean()))
    mesh = dirs.figure.axes[0].collections[0]
    drawn = np.ma.masked_invalid(np.asarray(mesh.get_array(), float)).compressed()
    np.testing.assert_array_equal(np.sort(drawn), np.sort(d["S_map"][inside]))


def test_directions_unknown_scheme_and_pick(dirs):
    dirs.set_state({"scheme": "LogP", "gamma": 90.0, "azimuth": 0.0})
    good = dirs.data
    dirs.controls["scheme"].value = "ZP2+Bogus"
    assert "unknown scheme" in dirs.error and "unknown scheme" in dirs.message.value and dirs.data is good
    dirs.controls["scheme"].value = "FPc+LogP"
    assert dirs.error is None and dirs.data["maps_max"] > 1
    assert dirs.pick(0.5, 0.3)  # a click at (u, v) on the map
    lv = dirs.data["light"]
    assert lv[2] == pytest.approx(0.5) and lv[0] == pytest.approx(0.3)
    with pytest.raises(ValueError, match="outside the hemisphere"):
        dirs.pick(0.9, 0.9)


def test_state_round_trips(dirs):
    dirs.set_state({"scheme": "ZP3+LogP", "f_over_n": 200.0, "gamma": 30.0})
    st = dirs.state()
    again = explore.directions(**st)
    assert again.state() == st
    np.testing.assert_array_equal(again.data["S_map"], dirs.data["S_map"])
    with pytest.raises(ValueError, match="unknown control"):
        dirs.set_state({"colour": "red"})


def test_cascades_equal_splits_report():
    e = explore.cascades(method="log", k=4, warp="P", budget=4096**2, allocation="error", res_image=1024)
    rows = budgets.splits_report("log", 1.0, 1000.0, 4, fov=60.0, light="sphere:256", warp="P", budget=4096.0**2, res_image=1024.0,
                                 allocations=("error",))
    d = e.data
    assert [round(f, 3) for f in d["far_i"]] == [5.623, 31.623, 177.828, 1000.0]  # Lloyd 2006 eqs. 15-16
    np.testing.assert_array_equal(d["S_max"], [r["S_max"] for r in rows[:-1]])
    assert d["worst"] == rows[-1]["max_error[error]"]
    bars = [p.get_height() for p in e.figure.axes[1].patches if p.get_visible()]  # the drawn bars (unused slots hidden)
    np.testing.assert_array_equal(bars, d["error"])
    e.set_state({"method": "practical", "lam": 0.3, "allocation": "equal"})
    rows = budgets.splits_report("practical", 1.0, 1000.0, 4, fov=60.0, light="sphere:256", warp="P", budget=4096.0**2,
                                 res_image=1024.0, allocations=("equal",), lam=0.3)
    np.testing.assert_array_equal(e.data["far_i"], [r["far"] for r in rows[:-1]])
    good = e.data
    assert not e.set_state({"method": "godot", "k": 8})  # above the engine's maximum: a message, not a traceback
    assert "at most" in e.error and e.data is good
    assert not e.set_state({"k": 4, "warp": "Nope"})
    assert "unknown scheme" in e.error and e.data is good
    assert e.set_state({"warp": "LogP"}) and e.data["method"] == "godot"


def test_faces_equal_face_errors():
    e = explore.faces(variant="fpcs", parameterization="perspective", f_over_n=10.0, gamma=20.0, azimuth=30.0)
    lv = geometry.light_direction(20.0, 30.0)
    r = faces.face_errors("fpcs", "perspective", 1.0, 10.0, 60.0, lv)
    d = e.data
    np.testing.assert_array_equal(d["chosen"], faces.chosen_faces(lv[None], 60.0)[0])
    np.testing.assert_array_equal(d["S_i"], r.M_x[0] * r.M_z[0])
    assert d["S"] == float(r.S[0]) and d["maps"] == int(r.maps[0])
    assert len(d["labels"]) == r.M_x.shape[1]
    bars = [p.get_height() for p in e.figure.axes[1].patches]
    np.testing.assert_array_equal(bars, d["S_i"][d["M_x"] > 0])
    assert e.set_state({"variant": "fp", "gamma": 90.0, "azimuth": 0.0, "f_over_n": 1000.0, "parameterization": "logperspective"})
    assert e.data["chosen"].tolist() == [False, True, False, False, False]
    assert round(e.data["S"], 3) == 5.982  # ln(f/n)/(2 tan 30°), Lloyd 2006 eq. 19 (overhead, bottom face only)


def test_raster_equals_pictures_and_validate():
    e = explore.raster(scheme="P", light="gamma:60", f_over_n=50.0, image_res=32, budget=64 * 64)
    assert e.error is None, e.error
    v = pictures.view(1.0, 50.0, 60.0, "gamma:60", "P", image_res=32, budget=64 * 64)
    np.testing.assert_array_equal(e.data["shaded"], pictures.shade(v))
    np.testing.assert_array_equal(e.data["error"], pictures.error_field(v), strict=False)
    val = validate("P", 50.0, 60.0, "gamma:60", res=64, probes=8)  # the ratios are measured at >= 64 pixels
    assert float(e.data["ratio_M_x"][0]) == val["ratio_M_x"] and float(e.data["ratio_M_z"][0]) == val["ratio_M_z"]
    good = e.data
    e.controls["light"].value = "gamma=60"
    assert "malformed light" in e.error and e.data is good
    e.controls["light"].value = "gamma:60@azimuth:10"
    assert e.error is None


def test_updates_are_debounced_in_a_running_loop(ov):
    async def drag():
        ov.debounce = 0.05
        before = ov.updates
        for value in (10.0, 20.0, 30.0):
            ov.controls["f_over_n"].value = value
        assert ov.updates == before  # nothing yet: waiting for the last change
        await asyncio.sleep(0.3)
        return ov.updates - before

    assert asyncio.run(drag()) == 1
    assert ov.data["f_over_n"] == 30.0


def test_without_the_extra_import_works_and_explorers_say_which_extra():
    code = (
        "import sys; sys.modules['ipywidgets'] = None\n"
        "import aliasing, aliasing.explore\n"
        "assert not aliasing.explore.available()\n"
        "try:\n    aliasing.explore.overhead()\n"
        "except ImportError as exc:\n    print(exc)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    lines = out.stdout.strip().splitlines()
    assert len(lines) == 1 and "pip install \".[explore]\"" in lines[0]


@pytest.mark.parametrize("name, change", [("overhead", {"f_over_n": 300.0}), ("overhead", {"aspect": 2.0}), ("cascades", {"aspect": 16 / 9}),
                                          ("directions", {"f_over_n": 300.0, "resolution": 24}),
                                          ("faces", {"gamma": 58.0}), ("cascades", {"lam": 0.3, "allocation": "error"})])
def test_redraw_in_place_gives_the_picture_of_a_fresh_explorer(name, change):
    make = getattr(explore, name)
    e = make(**({"resolution": 24} if name == "directions" else {}))
    artists = e._artists
    assert e.set_state(change)
    assert e._artists is artists  # updated in place, not drawn anew
    assert e.png() == make(**e.state()).png()
