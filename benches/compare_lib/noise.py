"""The simulation's step-time noise band (standard library only: benches/sim_compare.py
runs on the system Python)."""


def step_spread(perturbed_ms, mesh_ms):
    """How far the perturbed mesh's median step lies from the mesh's own (same geometry,
    chaotic piles, timer jitter), at least 2%: a ratio within 1 ± this is a tie."""
    return max(0.02, abs(perturbed_ms / mesh_ms - 1))
