"""Joint outputs of a run with a pretension section (docs/bolts.md, "Joint outputs").

    from k2d.joint import joint_history, joint_summary
    h = joint_history(Result("bolt_joint.h5"))      # per kept increment
    s = joint_summary(h)                              # F_V, Phi, k_S, k_P, separation load

From the documented result layout only (docs/results-format.md):

* the bolt force F_S: the section's `pretension_force` (first section, or `section`);
* the external (service) load F_A: the sum of the axial reactions -- the preload is internal to
  the joint, so the supports carry exactly the service load (ring totals in axisymmetry);
* the clamp force F_K: the sum of the normal forces of the joint interface's pairs (`interface`,
  default 1: the clamped parts' joint);
* the preload F_V: F_S at the last increment before the service load starts;
* the load factor Phi = dF_S/dF_A at the start of the service load (the first increments with
  F_A > 0 while the joint is closed), so that F_S = F_V + Phi F_A, F_K = F_V - (1 - Phi) F_A;
* k_S and k_P from the section's shortening at the preload, delta_V = F_V (1/k_S + 1/k_P), and Phi
  = k_S/(k_S + k_P) (load introduced at the head and nut, n = 1: for a load introduced inside the
  clamped parts Phi is n Phi_K and the split is that of the substitute springs);
* the separation load: F_A where F_K reaches zero (linear interpolation between increments), or
  None when the run does not get there.
"""
import numpy as np

__all__ = ["joint_history", "joint_summary", "interface_pressure"]


def joint_history(res, section=1, interface=1):
    """Per kept increment: dict of arrays F_A, F_S, F_K, shortening, steps."""
    iface = np.asarray(res.contact.interface) if res.contact is not None else None
    fa, fs, fk, sh, steps = [], [], [], [], []
    for s in res.steps:
        if "pretension_force" not in s.attrs:
            continue
        fs.append(float(np.atleast_1d(s.attrs["pretension_force"])[section - 1]))
        sh.append(float(np.atleast_1d(s.attrs["pretension_shortening"])[section - 1]))
        fa.append(float(np.sum(s.field("reaction")[:, 1])))
        if iface is not None:
            fn = s.contact("force_normal")
            fk.append(float(np.sum(fn[iface == interface])))
        else:
            fk.append(np.nan)
        steps.append(s.number)
    return {"F_A": np.abs(np.array(fa)), "F_S": np.array(fs), "F_K": np.array(fk),
            "shortening": np.array(sh), "steps": np.array(steps)}


def joint_summary(h, nfit=2):
    """F_V, Phi, k_S, k_P, delta_V and the separation load from a joint_history."""
    fa, fs, fk = h["F_A"], h["F_S"], h["F_K"]
    scale = max(np.max(np.abs(fs)), 1e-300)
    loaded = np.where(fa > 1e-9 * scale)[0]
    if len(loaded) == 0:
        return {"F_V": float(fs[-1]), "Phi": None, "k_S": None, "k_P": None, "delta_V": float(h["shortening"][-1]),
                "separation": None}
    i0 = max(loaded[0] - 1, 0)
    f_v = float(fs[i0])
    delta_v = float(h["shortening"][i0])
    fit = loaded[:nfit]
    phi = float(np.polyfit(np.r_[fa[i0], fa[fit]], np.r_[fs[i0], fs[fit]], 1)[0])
    k_s = f_v / (delta_v * (1.0 - phi)) if delta_v > 0 and phi < 1 else None
    k_p = f_v / (delta_v * phi) if delta_v > 0 and phi > 0 else None
    sep = None
    for k in range(1, len(fa)):
        if fk[k - 1] > 0.0 >= fk[k] and fa[k] > fa[k - 1]:
            sep = float(fa[k - 1] + (fa[k] - fa[k - 1]) * fk[k - 1] / (fk[k - 1] - fk[k]))
            break
    return {"F_V": f_v, "Phi": phi, "k_S": k_s, "k_P": k_p, "delta_V": delta_v, "separation": sep}


def interface_pressure(res, step, interface=1):
    """(r, p, contact radius) of the interface's pairs at `step` (a Step), sorted by r; the contact
    radius is the largest r of a closed pair (0 if none)."""
    iface = np.asarray(res.contact.interface)
    sel = iface == interface
    r = np.asarray(res.contact.position)[sel, 0]
    p = np.asarray(step.contact("pressure"))[sel]
    ns = np.asarray(step.contact("normal_state"))[sel]
    order = np.argsort(r)
    closed = r[ns > 0]
    return r[order], p[order], (float(np.max(closed)) if len(closed) else 0.0)
