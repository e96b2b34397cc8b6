"""Writes pxr_groom.usdc (and its text twin pxr_groom.usda) with Pixar's USD
(usd-core): the fixture crates/formats/tests/usdc_pxr.rs reads.

    python3 make_pxr_groom.py OUT_DIR

A groom as DCC tools write one: centimetres, Z up, a transformed parent,
three time samples of points, per-point widths of three distinct values
(stored as a lookup table), curve counts (integer coded), a static prim
with whole-number per-strand widths (stored as integers) and colours, and
prims a reader must skip (a class, an inactive prim).
"""
import os
import sys

from pxr import Gf, Sdf, Usd, UsdGeom

out = sys.argv[1]
path = os.path.join(out, "pxr_groom.usdc")
stage = Usd.Stage.CreateNew(path)
UsdGeom.SetStageMetersPerUnit(stage, 0.01)
UsdGeom.SetStageUpAxis(stage, UsdGeom.Tokens.z)
stage.SetTimeCodesPerSecond(30)
stage.SetStartTimeCode(1)
stage.SetEndTimeCode(3)
root = UsdGeom.Xform.Define(stage, "/groom")
root.AddTranslateOp().Set(Gf.Vec3d(1, 2, 3))
root.AddRotateXYZOp().Set(Gf.Vec3f(0, 0, 30))

hair = UsdGeom.BasisCurves.Define(stage, "/groom/hair")
hair.CreateTypeAttr().Set("linear")
hair.CreateCurveVertexCountsAttr().Set([5] * 20)
points = [Gf.Vec3f(i * 0.5, j * 0.25, j * 1.5) for i in range(20) for j in range(5)]
for time in (1, 2, 3):
    hair.CreatePointsAttr().Set([p + Gf.Vec3f(0, 0.125 * time, 0) for p in points], time)
hair.CreateWidthsAttr().Set([0.01 * (k % 3 + 1) for k in range(100)])
hair.SetWidthsInterpolation(UsdGeom.Tokens.vertex)

static = UsdGeom.BasisCurves.Define(stage, "/groom/static")
static.CreateTypeAttr().Set("linear")
static.CreateCurveVertexCountsAttr().Set([3] * 16)
static.CreatePointsAttr().Set(
    [Gf.Vec3f(-i, 0.5 * j, 2 * j + 0.25) for i in range(16) for j in range(3)])
static.CreateWidthsAttr().Set([float(k + 1) for k in range(16)])
static.SetWidthsInterpolation(UsdGeom.Tokens.uniform)
static.CreateDisplayColorAttr().Set([Gf.Vec3f(0.25, 0.5, 0.75)] * 16)
UsdGeom.Primvar(static.GetDisplayColorAttr()).SetInterpolation(UsdGeom.Tokens.uniform)

cls = stage.CreateClassPrim("/_template")
UsdGeom.BasisCurves.Define(stage, "/_template/hair").CreatePointsAttr().Set([Gf.Vec3f(9, 9, 9)])
off = UsdGeom.BasisCurves.Define(stage, "/groom/off")
off.CreateCurveVertexCountsAttr().Set([2])
off.CreatePointsAttr().Set([Gf.Vec3f(7, 7, 7), Gf.Vec3f(8, 8, 8)])
off.GetPrim().SetActive(False)
stage.GetRootLayer().Save()
stage.GetRootLayer().Export(os.path.join(out, "pxr_groom.usda"))
