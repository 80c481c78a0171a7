"""The shared flow field (core/flow.py) and the engines' map controls (engines/base.Controls)."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from svgtile.core.flow import FlowField
from svgtile.core.region import Region
from svgtile.engines import ENGINES, Controls, synthesize
from svgtile.engines.base import honoured
from svgtile.errors import ParameterError


def test_straight_stroke_gives_its_direction_everywhere():
    field = FlowField.from_strokes([np.array([[0.0, 0.0], [10.0, 10.0]])])
    xy = np.random.default_rng(0).uniform(-50, 50, (200, 2))
    assert np.allclose(field.angle(xy), 45.0, atol=1e-6)
    assert np.allclose(np.hypot(*field.direction(xy).T), 1.0)


def test_drawing_direction_matters():
    back = FlowField.from_strokes([np.array([[10.0, 0.0], [0.0, 0.0]])])
    assert np.allclose(np.abs(back.angle(np.array([[3.0, 4.0]]))), 180.0)


def test_a_bending_stroke_turns_the_field_with_it():
    t = np.linspace(0, np.pi / 2, 60)
    arc = np.c_[100 * np.cos(t), 100 * np.sin(t)]  # a quarter circle, drawn counter-clockwise
    field = FlowField.from_strokes([arc])
    on = arc[5:-5]
    want = np.degrees(np.arctan2(on[:, 0], -on[:, 1]))  # the circle's tangent there
    assert np.abs((field.angle(on) - want + 180) % 360 - 180).max() < 5.0


def test_two_strokes_blend_between_them():
    field = FlowField.from_strokes([np.array([[0.0, 0.0], [100.0, 0.0]]), np.array([[0.0, 100.0], [0.0, 200.0]])])
    a_low, a_high = field.angle(np.array([[50.0, 0.0], [0.0, 150.0]]))
    assert abs(a_low) < 5 and abs(a_high - 90) < 5


def test_no_stroke_is_an_error():
    with pytest.raises(ParameterError, match="--flow"):
        FlowField.from_strokes([np.array([[1.0, 1.0], [1.0, 1.0]])])


def test_uniform_field():
    assert np.allclose(FlowField.uniform(30.0).angle(np.array([[5.0, -7.0], [0.0, 0.0]])), 30.0)


@pytest.mark.parametrize("name", sorted(ENGINES))
def test_a_control_an_engine_does_not_honour_is_refused(name, tiny):
    from svgtile.svg.reader import read_exemplar

    engine, ex = ENGINES[name], read_exemplar(tiny)
    for control, value in (("flow", FlowField.uniform(0.0)), ("barriers", shapely.LineString([(0, 0), (9, 9)])),
                           ("grow_within", shapely.box(0, 0, 5, 5))):  # fmt: skip
        controls = Controls(**{control: value})
        if control in honoured(engine):
            continue
        with pytest.raises(ParameterError, match="cannot honour"):
            synthesize(ex, Region.rectangle(40, 40), name, seed=1, controls=controls)
