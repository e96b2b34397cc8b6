"""Writes alembic3d_groom.abc with the Alembic library's Python bindings
(PyAlembic, `alembic3d` on PyPI): the fixture crates/formats/tests/abc_alembic.rs
reads.

    python3 make_alembic_groom.py OUT_DIR

Curves as Maya or Houdini write them: under an Xform that translates by
(1, 2, 3) and turns 90 degrees about Y, 4 linear strands of 3 points
moving over 3 samples at 30 per second (P[i][j] at sample t is
(0.1 i, 0.5 - 0.1 j - 0.01 t, 0.02 j)), per-point widths; beside it, a
static object of 2 strands with one width per strand, written as an
indexed parameter; and a strand whose width is Unreal's `groom_width`
arbitrary parameter (0.5 mm for the whole strand).
"""
import os
import sys

import imath
from alembic3d.Abc import OArchive
from alembic3d.AbcCoreAbstract import TimeSampling
from alembic3d.AbcGeom import (CurvePeriodicity, CurveType, GeometryScope, OCurves,
                               OCurvesSchemaSample, OFloatGeomParam, OFloatGeomParamSample,
                               OXform, XformSample)

out = os.path.join(sys.argv[1], "alembic3d_groom.abc")
archive = OArchive(out)
index = archive.addTimeSampling(TimeSampling(1.0 / 30.0, 1.0 / 30.0))
xform = OXform(archive.getTop(), "groom", index)
sample = XformSample()
sample.setTranslation(imath.V3d(1, 2, 3))
sample.setYRotation(90.0)
xform.getSchema().set(sample)

hair = OCurves(xform, "hair", index)
counts = imath.IntArray(4)
for i in range(4):
    counts[i] = 3
for t in range(3):
    points = imath.V3fArray(12)
    widths = imath.FloatArray(12)
    for k in range(12):
        i, j = k // 3, k % 3
        points[k] = imath.V3f(0.1 * i, 0.5 - 0.1 * j - 0.01 * t, 0.02 * j)
        widths[k] = 0.001 * (1 + j)
    hair.getSchema().set(OCurvesSchemaSample(
        points, counts, CurveType.kLinear, CurvePeriodicity.kNonPeriodic,
        OFloatGeomParamSample(widths, GeometryScope.kVertexScope)))

still = OCurves(archive.getTop(), "still")
counts = imath.IntArray(2)
counts[0] = 2
counts[1] = 2
points = imath.V3fArray(4)
for k in range(4):
    points[k] = imath.V3f(-1.0 - k // 2, 0.25 * (k % 2), 0.0)
values = imath.FloatArray(1)
values[0] = 0.004
indices = imath.UnsignedIntArray(2)
indices[0] = 0
indices[1] = 0
still.getSchema().set(OCurvesSchemaSample(
    points, counts, CurveType.kLinear, CurvePeriodicity.kNonPeriodic,
    OFloatGeomParamSample(values, indices, GeometryScope.kUniformScope)))

unreal = OCurves(archive.getTop(), "unreal")
counts = imath.IntArray(1)
counts[0] = 2
points = imath.V3fArray(2)
points[0] = imath.V3f(2.0, 0.0, 0.0)
points[1] = imath.V3f(2.0, -0.5, 0.0)
unreal.getSchema().set(OCurvesSchemaSample(
    points, counts, CurveType.kLinear, CurvePeriodicity.kNonPeriodic))
groom_width = OFloatGeomParam(unreal.getSchema().getArbGeomParams(), "groom_width", False,
                              GeometryScope.kConstantScope, 1)
values = imath.FloatArray(1)
values[0] = 0.0005
groom_width.set(OFloatGeomParamSample(values, GeometryScope.kConstantScope))
