"""The keywords of Scene.render are the one settings description's names:
unknown names and impossible values are refused by name, the scene's own
suggestions sit under the caller's keywords, and every setting is documented."""

import math

import pytest

import candela


def test_unknown_keyword_is_refused_by_name():
    with pytest.raises(ValueError, match=r"unknown setting `sppp`"):
        candela.demo_scene().render(sppp=4, width=8, height=6)


@pytest.mark.parametrize("kwargs, start", [
    (dict(exposure=math.nan), "exposure=nan: expected a finite number"),
    (dict(focal_distance=0.0), "focal_distance (-d) 0"),
    (dict(width=100_000, height=100_000), "width, height (-r) 100000 100000: the film would need"),
    (dict(max_depth="deep"), "setting `max_depth`"),
    (dict(adaptive=(0, 0.05)), "adaptive (-a)"),
])
def test_impossible_values_are_refused(kwargs, start):
    with pytest.raises(ValueError) as err:
        candela.demo_scene().render(spp=1, **kwargs)
    assert str(err.value).startswith(start), str(err.value)


def test_scene_suggestions_sit_under_keywords():
    demo = candela.demo_scene()
    assert demo.settings()["camera"] == "file"  # the demo frames itself
    assert demo.settings(camera="cs184")["camera"] == "cs184"
    s = demo.settings(spp=3, width=20, height=10)
    assert (s["spp"], s["width"], s["height"], s["max_depth"]) == (3, 20, 10, 5)


def test_every_setting_is_documented():
    helps = candela.settings_help()
    for key in candela.demo_scene().settings():
        assert helps.get(key), f"setting {key} has no help"


def test_distributed_comes_with_the_package():
    assert candela.distributed.render is not None
    assert "time" in candela.distributed.UNSUPPORTED
