"""Non-rigid poses, API-wide: every public callable of octoreach._core that takes a 4x4 pose or an (N, 4, 4) batch
as an argument (options' pose fields are not swept) is called with each of these in turn in its first pose (the
other arguments valid, the call with them succeeding) and must raise a ValueError that says "rigid transform",
never answer: a scaled rotation, a sheared one, a reflection, a zero rotation and a last row other than 0 0 0 1.
A pose nobody meant would otherwise get an answer (a lookup normalises the approach direction of a scaled
rotation, a shear tilts it).

Signatures and valid values come from the wrong-types sweep (test_wrong_types.py), so a function added later is
swept without editing this file."""
from __future__ import annotations

import numpy as np
import pytest

from octoreach import _core
from test_non_finite import _outcome, _valid, world  # noqa: F401 - the non-finite sweep's fixture, reused
from test_wrong_types import _required, swept_signatures, sweep  # noqa: F401


def _scaled(R):
    return 2.0 * R


def _sheared(R):
    S = R.copy()
    S[0, 1] += 0.5
    return S


def _reflected(R):
    return R @ np.diag([1.0, 1.0, -1.0])


def _zero(R):
    return np.zeros((3, 3))


BREAKS = {"scaled": _scaled, "sheared": _sheared, "reflected": _reflected, "zero": _zero}


def _is_pose_stack(v) -> bool:
    """True for a float array of 4x4 rigid transforms (a valid pose argument; a 4x4 grid of numbers is not one)."""
    if not isinstance(v, np.ndarray) or v.dtype.kind != "f" or v.ndim < 2 or v.shape[-2:] != (4, 4) or v.size == 0:
        return False
    T = v.reshape(-1, 4, 4)
    R = T[:, :3, :3]
    return bool(np.allclose(R.transpose(0, 2, 1) @ R, np.eye(3)) and np.allclose(T[:, 3], [0, 0, 0, 1]))


def non_rigid_variants(v):
    """(name, `v` with its first pose broken) for an array of poses, nothing for anything else."""
    if not _is_pose_stack(v):
        return []
    out = []
    for name, brk in BREAKS.items():
        a = v.copy()
        first = a.reshape(-1, 4, 4)[0]
        first[:3, :3] = brk(first[:3, :3])
        out.append((name, a))
    a = v.copy()
    a.reshape(-1, 4, 4)[0][3] = [0.0, 0.0, 0.1, 1.0]
    out.append(("last row", a))
    return out


def sweep_poses(world):
    """(label, argument, break, exception or None) for every pose argument of every callable whose call with the
    unbroken pose succeeds (else the break would prove nothing)."""
    for label, target, params in swept_signatures(world):
        n = _required(params)
        for i, (pname, ann, _) in enumerate(params):
            base = [_valid(world, label, qn, qa) for (qn, qa, _) in params[: max(i + 1, n)]]
            variants = non_rigid_variants(base[i])
            if not variants or _outcome(lambda: target(*base)) is not None:
                continue
            for name, v in variants:
                args = list(base)
                args[i] = v
                yield label, pname, name, _outcome(lambda: target(*args))


def test_every_pose_argument_rejects_non_rigid_transforms(world):
    accepted, wrong, n, swept = [], [], 0, set()
    for label, pname, name, err in sweep_poses(world):
        n += 1
        swept.add(label)
        if err is None:
            accepted.append(f"{label}({pname}: {name})")
        elif not isinstance(err, ValueError) or "rigid transform" not in str(err):
            wrong.append(f"{label}({pname}: {name}): {type(err).__name__}: {str(err)[:160]}")
    print(f"swept {n} calls of {len(swept)} callables")
    assert {"CapabilityMap.reachable", "CertifiedLookup.reachable", "CertifiedLookup.certain",
            "CertifiedLookup.solution", "Chain.ik"} <= swept
    assert not accepted, "non-rigid pose accepted:\n" + "\n".join(accepted)
    assert not wrong, "\n".join(wrong)


def test_pose_fields_of_options_reject_non_rigid_transforms(world):
    """The pose fields of the search options (where the chain and the capability map stand) by the same rule."""
    m = world["by_name"]["map"]
    cam = _core.DepthCamera(16, 12, 1.0, 3.0)
    for field in ("chain_base", "capability_base"):
        _core.score_views(m, cam, np.eye(4)[None], **{field: np.eye(4)})
        for name, bad in non_rigid_variants(np.eye(4)):
            with pytest.raises(ValueError, match="rigid transform"):
                _core.score_views(m, cam, np.eye(4)[None], **{field: bad})
