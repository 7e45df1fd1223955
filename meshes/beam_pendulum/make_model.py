#!/usr/bin/env python3
"""The flexible beam pendulum of M. Berzeri & A. A. Shabana ("Development of simple models for the
elastic forces in the absolute nodal coordinate formulation", J. Sound Vib. 235 (2000) 539-565):
a 1.2 m beam, A = 0.0018 m^2, I = 1.215e-8 m^4, rho = 5540 kg/m^3, E = 0.7 MPa, pinned at one end,
released from the horizontal at rest under gravity. Printed as a model file (runtime/MODEL_FILE.md).
Usage: make_model.py FORMULATION END_TIME [ELEMENTS]
  FORMULATION: geometrically_exact (a revolute pin about y: a planar swing) or ancf (a spherical
  pin: the ancf node has no rotation for a revolute joint; the motion stays planar by symmetry)."""
import json
import sys

form, end = sys.argv[1], float(sys.argv[2])
elements = int(sys.argv[3]) if len(sys.argv) > 3 else 16
I = 1.215e-8
beam = {"name": "beam", "type": "beam", "formulation": form, "start": [0, 0, 0], "end": [1.2, 0, 0],
        "elements": elements, "E": 0.7e6, "rho": 5540, "section": {"A": 0.0018, "Iy": I, "Iz": I}}
if form == "geometrically_exact":
    # The benchmark's element has no shear and no torsion: nu = 0 and the full shear factor keep
    # the shear stiffness as high as the theory allows (kGA = EA / 2); J only holds the twist.
    beam.update({"nu": 0.0, "y_axis": [0, 1, 0]})
    beam["section"].update({"J": 2 * I, "shear_factor": 1.0})
    pin = {"name": "pin", "type": "revolute", "body1": "ground", "body2": "beam", "node2": "start", "axis": [0, 1, 0]}
else:
    pin = {"name": "pin", "type": "spherical", "body1": "ground", "body2": "beam", "node2": "start"}
model = {
    "gravity": [0, 0, -9.81],
    "bodies": [beam],
    "joints": [pin],
    "solver": {"end": end, "step": 1e-3},
    "outputs": [{"name": "tip", "type": "node_position", "body": "beam", "node": "end"},
                {"name": "middle", "type": "node_position", "body": "beam", "node": f"n{elements // 2}"},
                {"name": "energy", "type": "energy"}],
}
print(json.dumps(model, indent=2))
