# Runs inside YADE (`yade -n -j THREADS -x yade_packing.py IN.json OUT.json`), called by
# packing_vs_yade.py: the same tetrahedra as dspdem's packing, as rigid YADE polyhedra in the
# same open box, timed for a number of steps. IN.json: particles (four vertices each), density,
# young, poisson, friction, damping, gravity, box, steps. OUT.json: seconds per step, dt,
# interactions at the end.
import json
import math
import sys
import time

from yade import polyhedra_utils

src, dst = sys.argv[1], sys.argv[2]
p = json.load(open(src))


def inradius(v):
    # r = 3 V / (total face area): the tetrahedron's inscribed sphere.
    a, b, c, d = [Vector3(*x) for x in v]
    vol = abs((b - a).dot((c - a).cross(d - a))) / 6.0
    area = sum(0.5 * ((q - o).cross(r - o)).norm() for o, q, r in ((a, b, c), (a, b, d), (a, c, d), (b, c, d)))
    return 3.0 * vol / area


# PolyhedraMat: `young` is the volumetric law's stiffness (normal force per overlap volume),
# `poisson` the ratio ks / kn. The density and friction are the dspdem case's.
mat = PolyhedraMat(density=p["density"], young=p["young"], poisson=p["poisson"],
                   frictionAngle=math.atan(p["friction"]))
O.materials.append(mat)
for v in p["particles"]:
    O.bodies.append(polyhedra_utils.polyhedra(mat, v=[Vector3(*x) for x in v]))
# The open box as infinite walls: floor y = 0, x = 0 and x = box_x, z = 0 and z = box_z. The
# particles start over the footprint and fall straight in, so the walls' infinite extent above
# the rim changes nothing.
bx, bz = p["box"]
for pos, axis in ((0.0, 1), (0.0, 0), (bx, 0), (0.0, 2), (bz, 2)):
    O.bodies.append(wall(pos, axis, material=mat))

radii = [inradius(v) for v in p["particles"]]
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Polyhedra_Aabb(), Bo1_Wall_Aabb()], verletDist=0.05 * sum(radii) / len(radii)),
    InteractionLoop(
        [Ig2_Wall_Polyhedra_PolyhedraGeom(), Ig2_Polyhedra_Polyhedra_PolyhedraGeom()],
        [Ip2_PolyhedraMat_PolyhedraMat_PolyhedraPhys()],
        [Law2_PolyhedraGeom_PolyhedraPhys_Volumetric()],
    ),
    # The volumetric law has no viscous term; YADE's local (non-viscous) damping stands in
    # for dspdem's contact damping. It costs the same per step either way.
    NewtonIntegrator(damping=p["damping"], gravity=Vector3(*p["gravity"])),
]
# PWaveTimeStep() returns 1.0 s for polyhedra here and the run blows up: the step by hand.
r_min = min(radii)
O.dt = 0.5 * r_min / math.sqrt(p["young_material"] / p["density"])
O.run(1, True)  # the collider's first sort and the bodies' set-up are not steps
t0 = time.perf_counter()
O.run(p["steps"], True)
wall_s = time.perf_counter() - t0
ok = all(math.isfinite(b.state.pos.norm()) for b in O.bodies)
json.dump({"steps": p["steps"], "wall_s": wall_s, "s_per_step": wall_s / p["steps"], "dt": O.dt,
           "interactions": sum(1 for i in O.interactions if i.isReal), "finite": ok,
           "threads": O.numThreads}, open(dst, "w"))
O.exitNoBacktrace()
