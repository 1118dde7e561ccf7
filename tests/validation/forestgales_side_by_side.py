#!/usr/bin/env python3
"""ForestGALES side by side: the critical wind speeds of trees by ForestGALES's two methods, from the papers.

An independent check for issue 45 (storm damage, docs/damage.md): it shares no code with forestwind and
depends on nothing beyond the Python standard library. Each equation below names its source; the values the
papers do not give us are "stand-ins", each named where it is used and listed in the output.

Usage:
    python3 tests/validation/forestgales_side_by_side.py                  # the built-in trees, a text table
    python3 tests/validation/forestgales_side_by_side.py --json           # the same as JSON
    python3 tests/validation/forestgales_side_by_side.py --trees FILE.csv
    python3 tests/validation/forestgales_side_by_side.py --tree sitka_spruce,20,0.25,2.5 --tree ...
    python3 tests/validation/forestgales_side_by_side.py --self-test      # exit 0 if the worked example holds

CSV columns (a header row with these names, or the same order without a header):
    species,height_m,dbh_m,spacing_m[,crown_depth_m,crown_width_m,soil,rooting]
species: sitka_spruce | norway_spruce | scots_pine | birch (spaces, hyphens and case are ignored);
soil: A (free-draining mineral) | B (gleyed mineral) | C (peaty mineral) | D (deep peat), default A;
rooting: shallow | mean | deep (shallow and deep on soil A only), default mean. An optional column
stem_volume_m3 replaces the stem-volume stand-in. Empty optional fields take their defaults.

The model (SI units throughout):

Critical moments (Gardiner et al. 2000, 2008; Hale et al. 2015; species table of ForestGALES):
    breakage      M_b = f_knot MOR pi (1.03 dbh)^3 / 32, at the stem base, whose diameter ForestGALES
                  takes as 1.03 dbh;
    overturning   M_o = C_reg W_stem, W_stem = stem volume x green density, C_reg the tree-pulling
                  regression through zero by species, soil group and rooting (Nicoll et al. 2006).
    Stem volume: ForestGALES takes it from species volume equations (fgr's documentation names Fonweban et
    al. 2012 for the British conifers), whose coefficients we do not have. Stand-in (--stem-volume):
        bh-paraboloid (default)  V = (pi/8) dbh^2 (h - 1.3): a quadratic paraboloid through dbh at 1.3 m, its
                                 volume above breast height. Extended to the ground the same paraboloid is
                                 dbh sqrt(h / (h - 1.3)) across, 1.034 dbh at h = 20 m: ForestGALES's 1.03.
                                 It gives the worked example's M_o of 61 kN m (a stem of 0.459 m^3).
        paraboloid               V = (pi/8) (1.03 dbh)^2 h      (69 kN m in the worked example)
        cone                     V = (pi/12) (1.03 dbh)^2 h     (46 kN m in the worked example)
    Which of the two fails first: the one with the smaller critical moment. Both methods load the stem base
    with the same moment, proportional to u_h^2, so the order is the same for both methods and positions.

The lean (Hale et al. 2015): the bent tree's weight adds a moment; ForestGALES's "deflection loading
factor" f_lean multiplies the wind's moment, about 1.14 by default (--lean-factor, --no-lean). The
single-tree method uses that constant. ForestGALES's roughness method computes its factor from the stem's
deflection (MOE, stem and crown weight; Gardiner et al. 2000); here it takes the same constant (stand-in).

Single-tree method (Hale et al. 2012; Hale et al. 2015):
    M_max = f_lean E T_C u_h^2,  T_C = 111.6 dbh^2 h,   u_h the hourly mean wind at the canopy top;
    u_h,crit = sqrt(M_crit / (f_lean E T_C)).
    E is 1 for an interior tree. For an edge tree, E is the edge's maximum moment over the interior's, from
    Gardiner et al. 2000's wind-tunnel fit below: E = Max(x/h) / Max(inf). (ForestGALES 2.5 applies that
    edge fit in its single-tree method too, Hale et al. 2015; the ratio of the two maxima is how this script
    reads it, since T_C is already an interior tree's peak: not checked against the paper's text.)

Roughness method (Gardiner et al. 2000):
    M_max = f_lean d rho G (D u*)^2: the canopy's shear stress rho u*^2 on a tree's share D^2 of the ground,
    acting at the zero-plane displacement d (Thom 1971), times the gust factor G; D the mean spacing.
    Canopy (Raupach 1994, constants c_d1 7.5, C_S 0.003, C_R 0.3, psi_h 0.193, (u*/U_h)_max 0.3, kappa 0.4):
        lambda  = frontal area of a crown / D^2; the crown's silhouette a triangle, cw cd / 2 (stand-in:
                  no published ForestGALES crown shape at hand; a rigid crown, no streamlining, see below);
        d/h     = 1 - (1 - exp(-sqrt(c_d1 2 lambda))) / sqrt(c_d1 2 lambda);
        u*/U_h  = min(sqrt(C_S + C_R lambda), (u*/U_h)_max);
        z0/h    = (1 - d/h) exp(-kappa U_h/u* + s psi_h), s = +1 by default (--psi-h-sign): see below.
    u* from u_h (--ustar): "raupach" (default) u* = (u*/U_h) u_h; "loglaw" u* = kappa u_h / ln((h - d)/z0),
    the log profile through the canopy top with Raupach's d and z0, the form of Gardiner et al. 2000.
    Gust factor (Gardiner et al. 2000, a fit to the wind-tunnel moments of Gardiner et al. 1997), s/h = D/h,
    x the distance downwind of the edge, with an open fetch upwind (the wind tunnel's edge):
        Max(x/h)  = (2.7193 s/h - 0.061) + (-1.273 s/h + 0.9701) (1.1127 s/h + 0.0311)^(x/h)
        Mean(inf) = 0.68 s/h - 0.0385     (the mean moment's fit far from the edge)
        G(x)      = Max(x/h) / Mean(inf)
    Mean(inf) because the mean moment d rho (D u*)^2 is the interior stand's: G at the edge then carries the
    edge's larger peak. (The mean moment's fit has an edge term too, which G does not need.) G is finite
    and falls away from the edge only for s/h in (0.0566, 0.871), the script's limits; the fit was made
    for the spacings of the wind-tunnel stands and is an extrapolation beyond them.
    Interior: x -> inf, G = (2.7193 s/h - 0.061) / (0.68 s/h - 0.0385), 6.0 at s/h 0.125.
    The coefficients are Gardiner et al. 2000's as we know them; we could not read the paper's text here to
    check them. The interior value agrees with the published "about 6" at D/h = 0.125.
    Edge tree: x = 0 (--edge-distance-h). ForestGALES 2.5 also scales the edge term with the length of the
    upwind gap (Hale et al. 2015); we have not its published form, so the edge here is the wind tunnel's,
    open upwind (stand-in: gap factor 1).
    u_h,crit = sqrt(M_crit / (f_lean d rho G D^2 (u*/u_h)^2)).

Wind at 10 m above the zero-plane displacement (what ForestGALES reports, to compare with anemometers):
    u10 = (u*/kappa) ln(10 / z0), with the stand's d and z0 and the --ustar form, for both methods.

Air density: rho = 1.225 kg/m^3 (ISA sea level; stand-in for ForestGALES's value, which we do not have).

Raupach's z0 and psi_h: it is often quoted as z0/h = (1 - d/h) exp(-kappa U_h/u* - psi_h); the canopy
code Raupach co-wrote (CSIRO's CABLE land-surface model, its roughness module citing Raupach 1994) adds
psi_h, exp(-kappa U_h/u* + psi_h), which is what a roughness-sublayer profile U_h = (u*/kappa)(ln((h - d)
/z0) + psi_h), faster at the canopy top than the log law, gives. We could not read the paper's own text;
+psi_h is the default, --psi-h-sign - gives the other. The sign changes z0 by a factor exp(0.386) = 1.47,
and so u10 (and u* with --ustar loglaw); u_h,crit with --ustar raupach does not depend on it.

Streamlining: ForestGALES lowers a crown's frontal area as the wind rises (species drag parameters from
wind-tunnel measurements of trees, Mayhead 1973) and so iterates on u_h; we have not those parameters: the
crown is rigid (stand-in).

Sources: Gardiner, Peltola & Kellomaki 2000, Ecol. Model. 129:1-23; Gardiner et al. 2008, Forestry 81:447-463;
Hale et al. 2012, Eur. J. For. Res. 131:203-217 (T_C); Hale et al. 2015, Environ. Model. Softw. 68:27-41
(ForestGALES 2.5, the deflection loading factor); Nicoll et al. 2006, Can. J. For. Res. 36:1871 (C_reg);
Raupach 1994, Boundary-Layer Meteorol. 71:211-216; Thom 1971, Q. J. R. Meteorol. Soc. 97:414-428;
Gardiner et al. 1997, Forestry 70:233-252 (the wind tunnel); Mayhead 1973, Forestry 46:123-130.
"""

import argparse
import csv
import json
import math
import sys

# Raupach (1994): the constants of his simplified canopy expressions.
KAPPA = 0.4  # von Karman's constant
C_D1 = 7.5  # scales d/h
C_S = 0.003  # substrate drag coefficient
C_R = 0.3  # roughness-element drag coefficient
PSI_H = 0.193  # roughness-sublayer influence, ln c_w - 1 + 1/c_w with c_w = 2
USTAR_UH_MAX = 0.3  # the most u*/U_h can be

RHO_AIR = 1.225  # kg/m^3, ISA sea level (stand-in: ForestGALES's own value not at hand)
BASE_DIAMETER_FACTOR = 1.03  # ForestGALES: stem base diameter = 1.03 dbh
LEAN_FACTOR = 1.14  # Hale et al. 2015: the deflection loading factor, default
HALE_TC = 111.6  # Hale et al. 2012: T_C = 111.6 dbh^2 h, N m / (m/s)^2 with dbh, h in m
BREAST_HEIGHT = 1.3  # m

SOILS = ("A", "B", "C", "D")
ROOTINGS = ("shallow", "mean", "deep")


def _creg(a_shallow, a_deep, a_mean, b, c, d):
    return {("A", "shallow"): a_shallow, ("A", "deep"): a_deep, ("A", "mean"): a_mean,
            ("B", "mean"): b, ("C", "mean"): c, ("D", "mean"): d}


# ForestGALES's published species table (Gardiner et al. 2000, 2008; Hale et al. 2015; C_reg from the
# tree-pulling tests of Nicoll et al. 2006). MOR in Pa, green density in kg/m^3, C_reg in N m/kg.
SPECIES = {
    "sitka_spruce": {"name": "Sitka spruce", "mor": 34e6, "knot_factor": 1.0, "green_density": 850.0,
                     "c_reg": _creg(153.2, 178.1, 156.2, 138.5, 151.2, 172.1), "stand_in": None},
    "norway_spruce": {"name": "Norway spruce", "mor": 36e6, "knot_factor": 0.9, "green_density": 850.0,
                      "c_reg": _creg(126.0, 146.6, 128.5, 113.9, 124.4, 141.5), "stand_in": None},
    "scots_pine": {"name": "Scots pine", "mor": 46e6, "knot_factor": 0.85, "green_density": 850.0,
                   "c_reg": _creg(140.1, 162.9, 142.9, 126.7, 138.3, 157.3), "stand_in": None},
    # Birch: the Nordic MOR (53.6 MPa), a knot factor of 1 (a broadleaf's wood has no conifer's whorls of
    # knots), the conifers' 850 kg/m^3 and Norway spruce's C_reg, as forestwind's preset (stand-ins).
    "birch": {"name": "birch", "mor": 53.6e6, "knot_factor": 1.0, "green_density": 850.0,
              "c_reg": _creg(126.0, 146.6, 128.5, 113.9, 124.4, 141.5),
              "stand_in": "birch: MOR 53.6 MPa (Nordic); knot factor 1, green density and C_reg Norway "
                          "spruce's (stand-ins, as forestwind's birch preset)"},
}

# The built-in trees: the summary's worked example first, then one of each other species.
BUILT_IN = [
    {"species": "sitka_spruce", "height_m": 20.0, "dbh_m": 0.25, "spacing_m": 2.5},
    {"species": "norway_spruce", "height_m": 25.0, "dbh_m": 0.30, "spacing_m": 3.0, "soil": "B"},
    {"species": "scots_pine", "height_m": 18.0, "dbh_m": 0.22, "spacing_m": 2.8, "rooting": "deep"},
    {"species": "birch", "height_m": 16.0, "dbh_m": 0.18, "spacing_m": 3.0,
     "crown_depth_m": 8.0, "crown_width_m": 3.5},
]

# Stand-ins for a tree's crown when not given.
CROWN_DEPTH_FRACTION = 0.35  # crown depth = 0.35 h
# crown width = the spacing (a closed canopy)

CSV_COLUMNS = ["species", "height_m", "dbh_m", "spacing_m", "crown_depth_m", "crown_width_m", "soil",
               "rooting"]


class InputError(ValueError):
    pass


def species_key(word):
    key = word.strip().lower().replace(" ", "_").replace("-", "_")
    if key not in SPECIES:
        raise InputError(f"unknown species {word!r} (expected one of {', '.join(SPECIES)})")
    return key


# ---- critical moments -------------------------------------------------------------------------------------

def stem_volume(height, dbh, form):
    """m^3: the stand-in stem of --stem-volume."""
    if form == "bh-paraboloid":
        if height <= BREAST_HEIGHT:
            raise InputError(f"height {height} m: bh-paraboloid needs a tree taller than {BREAST_HEIGHT} m")
        return math.pi / 8.0 * dbh ** 2 * (height - BREAST_HEIGHT)
    base = BASE_DIAMETER_FACTOR * dbh
    if form == "paraboloid":
        return math.pi / 8.0 * base ** 2 * height
    if form == "cone":
        return math.pi / 12.0 * base ** 2 * height
    raise InputError(f"unknown stem volume form {form!r}")


def breaking_moment(sp, dbh):
    """M_b = f_knot MOR pi (1.03 dbh)^3 / 32, N m."""
    d = BASE_DIAMETER_FACTOR * dbh
    return sp["knot_factor"] * sp["mor"] * math.pi * d ** 3 / 32.0


def overturning_moment(sp, soil, rooting, volume):
    """M_o = C_reg x green density x stem volume, N m."""
    key = (soil, rooting)
    if key not in sp["c_reg"]:
        raise InputError(f"no C_reg for soil {soil} with {rooting} rooting (shallow and deep: soil A only)")
    return sp["c_reg"][key] * sp["green_density"] * volume


# ---- canopy (Raupach 1994) ---------------------------------------------------------------------------------

def canopy(height, spacing, crown_width, crown_depth, psi_sign):
    lam = 0.5 * crown_width * crown_depth / spacing ** 2  # triangular silhouette / D^2
    x = math.sqrt(C_D1 * 2.0 * lam)
    d_over_h = 1.0 - (1.0 - math.exp(-x)) / x
    ustar_uh = min(math.sqrt(C_S + C_R * lam), USTAR_UH_MAX)
    z0_over_h = (1.0 - d_over_h) * math.exp(-KAPPA / ustar_uh + psi_sign * PSI_H)
    return {"lambda": lam, "d_m": d_over_h * height, "z0_m": z0_over_h * height,
            "ustar_over_uh_raupach": ustar_uh}


def ustar_over_uh(can, height, form):
    if form == "raupach":
        return can["ustar_over_uh_raupach"]
    if form == "loglaw":
        return KAPPA / math.log((height - can["d_m"]) / can["z0_m"])
    raise InputError(f"unknown u* form {form!r}")


# ---- gust factor (Gardiner et al. 2000) --------------------------------------------------------------------

def max_moment_fit(s_h, x_h):
    """Gardiner et al. 2000: the maximum moment's fit against s/h and x/h (x/h = inf: the interior)."""
    base = 1.1127 * s_h + 0.0311
    decay = 0.0 if math.isinf(x_h) else base ** x_h
    return (2.7193 * s_h - 0.061) + (-1.273 * s_h + 0.9701) * decay


def mean_moment_interior(s_h):
    """Gardiner et al. 2000: the mean moment's fit far from the edge, (0.68 s/h - 0.0385)."""
    return 0.68 * s_h - 0.0385


def check_spacing_ratio(s_h):
    # Where the fit gives a finite, positive G decaying away from the edge: the interior mean moment
    # 0.68 s/h - 0.0385 > 0 (s/h > 0.0566) and the decay base 1.1127 s/h + 0.0311 < 1 (s/h < 0.871).
    if not (mean_moment_interior(s_h) > 0.0 and 1.1127 * s_h + 0.0311 < 1.0):
        raise InputError(f"spacing/height {s_h:.4f}: outside (0.0566, 0.871), where Gardiner et al. "
                         f"2000's gust-factor fit is finite")


def gust_factor(s_h, x_h):
    check_spacing_ratio(s_h)
    return max_moment_fit(s_h, x_h) / mean_moment_interior(s_h)


def edge_factor(s_h, x_h):
    check_spacing_ratio(s_h)
    return max_moment_fit(s_h, x_h) / max_moment_fit(s_h, math.inf)


# ---- a tree ------------------------------------------------------------------------------------------------

def parse_float(value, name, default=None):
    if value is None or str(value).strip() == "":
        if default is None:
            raise InputError(f"{name}: a number expected, got nothing")
        return default
    try:
        v = float(value)
    except ValueError:
        raise InputError(f"{name}: a number expected, got {value!r}") from None
    if not (math.isfinite(v) and v > 0.0):
        raise InputError(f"{name}: a finite positive number expected, got {value!r}")
    return v


def normalise_tree(row):
    """A tree's inputs with defaults and stand-ins; raises InputError naming the bad field."""
    sp = species_key(row.get("species") or "")
    h = parse_float(row.get("height_m"), "height_m")
    dbh = parse_float(row.get("dbh_m"), "dbh_m")
    D = parse_float(row.get("spacing_m"), "spacing_m")
    stand_ins = []
    if row.get("crown_depth_m") in (None, ""):
        cd = CROWN_DEPTH_FRACTION * h
        stand_ins.append(f"crown depth {cd:.2f} m = {CROWN_DEPTH_FRACTION} h (stand-in: not given)")
    else:
        cd = parse_float(row["crown_depth_m"], "crown_depth_m")
    if row.get("crown_width_m") in (None, ""):
        cw = D
        stand_ins.append(f"crown width {cw:.2f} m = the spacing, a closed canopy (stand-in: not given)")
    else:
        cw = parse_float(row["crown_width_m"], "crown_width_m")
    if cd > h:
        raise InputError(f"crown_depth_m {cd} is more than the height {h}")
    soil = (row.get("soil") or "A").strip().upper()
    if soil not in SOILS:
        raise InputError(f"soil {soil!r}: one of A, B, C, D expected")
    rooting = (row.get("rooting") or "mean").strip().lower()
    if rooting not in ROOTINGS:
        raise InputError(f"rooting {rooting!r}: shallow, mean or deep expected")
    if dbh >= h:
        raise InputError(f"dbh_m {dbh} is not less than height_m {h}")
    if (soil, rooting) not in SPECIES[sp]["c_reg"]:
        raise InputError(f"no C_reg for soil {soil} with {rooting} rooting (shallow and deep: soil A only)")
    volume = row.get("stem_volume_m3")
    volume = None if volume in (None, "") else parse_float(volume, "stem_volume_m3")
    return {"species": sp, "height_m": h, "dbh_m": dbh, "spacing_m": D, "crown_depth_m": cd,
            "crown_width_m": cw, "soil": soil, "rooting": rooting, "stem_volume_m3": volume,
            "stand_ins": stand_ins}


def method_entry(moment_per_uh2, m_b, m_o, ustar_uh, z0, factor_name, factor):
    uh_b = math.sqrt(m_b / moment_per_uh2)
    uh_o = math.sqrt(m_o / moment_per_uh2)
    uh = min(uh_b, uh_o)
    ln10 = math.log(10.0 / z0)
    return {factor_name: factor, "moment_per_uh2_Nm_s2_m2": moment_per_uh2,
            "uh_crit_breakage_m_s": uh_b, "uh_crit_overturning_m_s": uh_o, "uh_crit_m_s": uh,
            "u10_crit_m_s": uh * ustar_uh / KAPPA * ln10,
            "fails_first": "breakage" if uh_b <= uh_o else "overturning"}


def evaluate(tree, opts):
    sp = SPECIES[tree["species"]]
    h, dbh, D = tree["height_m"], tree["dbh_m"], tree["spacing_m"]
    stand_ins = list(tree["stand_ins"])
    if sp["stand_in"]:
        stand_ins.append(sp["stand_in"])
    if tree["stem_volume_m3"] is not None:
        volume, volume_source = tree["stem_volume_m3"], "given"
    else:
        volume, volume_source = stem_volume(h, dbh, opts.stem_volume), opts.stem_volume + " (stand-in)"
    m_b = breaking_moment(sp, dbh)
    m_o = overturning_moment(sp, tree["soil"], tree["rooting"], volume)
    lean = opts.lean_factor

    can = canopy(h, D, tree["crown_width_m"], tree["crown_depth_m"], opts.psi_h_sign)
    if can["z0_m"] >= 10.0:
        raise InputError(f"z0 {can['z0_m']:.2f} m: 10 m above d is inside the roughness length")
    us = ustar_over_uh(can, h, opts.ustar)
    s_h = D / h
    x_h = opts.edge_distance_h

    t_c = HALE_TC * dbh ** 2 * h
    e_edge = edge_factor(s_h, x_h)
    single = {
        "interior": method_entry(lean * t_c, m_b, m_o, us, can["z0_m"], "edge_factor", 1.0),
        "edge": method_entry(lean * e_edge * t_c, m_b, m_o, us, can["z0_m"], "edge_factor", e_edge),
    }
    for entry in single.values():
        entry["T_C"] = t_c
    rough = {}
    for position, xh in (("interior", math.inf), ("edge", x_h)):
        g = gust_factor(s_h, xh)
        per_uh2 = lean * can["d_m"] * opts.rho * g * D ** 2 * us ** 2
        rough[position] = method_entry(per_uh2, m_b, m_o, us, can["z0_m"], "gust_factor", g)

    return {
        "label": tree.get("label", ""), "species": tree["species"], "species_name": sp["name"],
        "inputs": {k: tree[k] for k in ("height_m", "dbh_m", "spacing_m", "crown_depth_m", "crown_width_m",
                                        "soil", "rooting")},
        "critical_moments": {
            "breakage_Nm": m_b, "overturning_Nm": m_o,
            "fails_first": "breakage" if m_b <= m_o else "overturning",
            "base_diameter_m": BASE_DIAMETER_FACTOR * dbh, "stem_volume_m3": volume,
            "stem_volume_source": volume_source, "stem_weight_kg": volume * sp["green_density"],
            "mor_Pa": sp["mor"], "knot_factor": sp["knot_factor"],
            "c_reg_Nm_per_kg": sp["c_reg"][(tree["soil"], tree["rooting"])],
        },
        "canopy": dict(can, ustar_over_uh=us, spacing_over_height=s_h),
        "methods": {"single_tree": single, "roughness": rough},
        "stand_ins": stand_ins,
    }


def settings_of(opts):
    return {
        "lean_factor": opts.lean_factor, "ustar": opts.ustar, "psi_h_sign": opts.psi_h_sign,
        "stem_volume": opts.stem_volume, "rho_air_kg_m3": opts.rho,
        "edge_distance_over_h": opts.edge_distance_h,
        "raupach": {"kappa": KAPPA, "c_d1": C_D1, "C_S": C_S, "C_R": C_R, "psi_h": PSI_H,
                    "ustar_over_uh_max": USTAR_UH_MAX},
        "hale_T_C_coefficient": HALE_TC, "base_diameter_factor": BASE_DIAMETER_FACTOR,
        "stand_ins": [
            "stem volume: " + opts.stem_volume + " (ForestGALES's species volume equations not at hand)",
            "roughness method's lean: the constant factor (ForestGALES computes it from the deflection)",
            "crown silhouette: a triangle, cw cd / 2; rigid crown (no streamlining)",
            "edge: a large upwind gap (gap factor 1); ForestGALES 2.5's gap factor not at hand",
            f"air density {opts.rho} kg/m^3 (ISA)",
        ],
    }


# ---- output ------------------------------------------------------------------------------------------------

def text_report(results, opts, out):
    s = settings_of(opts)
    out.write("ForestGALES side by side (critical winds from the papers' equations; "
              f"lean factor {opts.lean_factor:g}, u* {opts.ustar}, "
              f"psi_h sign {'+' if opts.psi_h_sign > 0 else '-'}, "
              f"stem volume {opts.stem_volume})\n")
    header = ("tree", "species", "method", "position", "factor", "M_b kNm", "M_o kNm", "fails first",
              "uh_b m/s", "uh_o m/s", "uh_crit", "u10_crit")
    rows = []
    for i, r in enumerate(results, 1):
        cm = r["critical_moments"]
        for method, key, fname, fmt in (("single-tree", "single_tree", "edge_factor", "E {:.2f}"),
                                        ("roughness", "roughness", "gust_factor", "G {:.2f}")):
            for position in ("interior", "edge"):
                m = r["methods"][key][position]
                rows.append((str(i), r["species_name"], method, position, fmt.format(m[fname]),
                             f"{cm['breakage_Nm'] / 1e3:.2f}", f"{cm['overturning_Nm'] / 1e3:.2f}",
                             m["fails_first"], f"{m['uh_crit_breakage_m_s']:.2f}",
                             f"{m['uh_crit_overturning_m_s']:.2f}", f"{m['uh_crit_m_s']:.2f}",
                             f"{m['u10_crit_m_s']:.2f}"))
    widths = [max(len(header[c]), *(len(row[c]) for row in rows)) for c in range(len(header))]
    line = lambda cells: "  ".join(c.rjust(w) if j >= 4 else c.ljust(w)
                                   for j, (c, w) in enumerate(zip(cells, widths))).rstrip()
    out.write(line(header) + "\n")
    out.write(line(["-" * w for w in widths]) + "\n")
    for row in rows:
        out.write(line(row) + "\n")
    out.write("\n")
    for i, r in enumerate(results, 1):
        inp, cm, can = r["inputs"], r["critical_moments"], r["canopy"]
        t_c = r["methods"]["single_tree"]["interior"]["T_C"]
        out.write(f"tree {i} ({r['label']}): {r['species_name']}, h {inp['height_m']:g} m, "
                  f"dbh {inp['dbh_m']:g} m, "
                  f"spacing {inp['spacing_m']:g} m, soil {inp['soil']}, {inp['rooting']} rooting; "
                  f"T_C {t_c:.1f} N m s^2/m^2; "
                  f"stem {cm['stem_volume_m3']:.3f} m^3 by {cm['stem_volume_source']}, "
                  f"{cm['stem_weight_kg']:.0f} kg; C_reg {cm['c_reg_Nm_per_kg']:g} N m/kg\n")
        out.write(f"  canopy: crown {inp['crown_width_m']:.2f} m x {inp['crown_depth_m']:.2f} m, "
                  f"lambda {can['lambda']:.3f}, D/h {can['spacing_over_height']:.3f}, d {can['d_m']:.2f} m, "
                  f"z0 {can['z0_m']:.3f} m, u*/u_h {can['ustar_over_uh']:.3f}\n")
        for note in r["stand_ins"]:
            out.write(f"  stand-in: {note}\n")
    out.write("\nstand-ins for every tree:\n")
    for note in s["stand_ins"]:
        out.write(f"  {note}\n")
    out.write("factor: E, the single-tree edge factor Max(x/h)/Max(inf); G, the roughness gust factor "
              "Max(x/h)/Mean(inf) (Gardiner et al. 2000).\n"
              "uh: hourly mean wind at the canopy top; u10: at 10 m above the zero-plane displacement.\n")


# ---- self-test ---------------------------------------------------------------------------------------------

def self_test(opts, out):
    """The summary's worked example: Sitka spruce, h 20 m, dbh 0.25 m, spacing 2.5 m, soil A, mean rooting."""
    defaults = build_parser().parse_args([])
    changed = [k for k, v in vars(opts).items()
               if k not in ("self_test", "json") and v != getattr(defaults, k)]
    if changed:
        out.write(f"self-test: {', '.join('--' + k.replace('_', '-') for k in changed)} ignored; the worked "
                  f"example is checked with the defaults\n")
    opts = defaults
    tree = normalise_tree(dict(BUILT_IN[0]))
    r = evaluate(tree, opts)
    cm = r["critical_moments"]
    single = r["methods"]["single_tree"]["interior"]
    t_c = single["T_C"]
    no_lean = argparse.Namespace(**vars(opts))
    no_lean.lean_factor = 1.0
    r_plain = evaluate(tree, no_lean)
    checks = []

    def check(name, value, lo, hi, reason):
        ok = lo <= value <= hi
        checks.append(ok)
        out.write(f"{'PASS' if ok else 'FAIL'}  {name} = {value:.4g}, expected [{lo:g}, {hi:g}]: {reason}\n")

    check("M_b (kN m)", cm["breakage_Nm"] / 1e3, 56.5, 57.5,
          "the worked example's 57 kN m, given to 2 figures (+-0.5)")
    check("M_o (kN m)", cm["overturning_Nm"] / 1e3, 60.5, 61.5,
          "the worked example's 61 kN m, given to 2 figures (+-0.5); depends on the stem-volume stand-in "
          "(bh-paraboloid)")
    check("T_C (N m s^2/m^2)", t_c, 139.45, 139.55, "the worked example's 139.5, given to 4 figures (+-0.05)")
    check("fails first is breakage (1 = yes)", 1.0 if cm["fails_first"] == "breakage" else 0.0, 1, 1,
          "M_b 57 < M_o 61 in the worked example")
    check("single-tree interior u_h,crit with lean 1.14 (m/s)", single["uh_crit_m_s"], 18.5, 19.0,
          "the worked example's range 18.5-19 m/s, sqrt(M_b / (1.14 T_C))")
    check("peak root moment T_C u_h^2 at 15 m/s, no lean (kN m)", t_c * 15.0 ** 2 / 1e3, 30.5, 31.5,
          "the worked example's 31 kN m, given to 2 figures (+-0.5)")
    check("single-tree u_h,crit without lean / with (ratio)",
          r_plain["methods"]["single_tree"]["interior"]["uh_crit_m_s"] / single["uh_crit_m_s"],
          math.sqrt(1.14) - 1e-9, math.sqrt(1.14) + 1e-9, "u_h,crit scales as f_lean^-1/2 (to rounding)")
    g = r["methods"]["roughness"]["interior"]["gust_factor"]
    check("roughness interior G at D/h 0.125", g, 5.9, 6.1,
          "the summary's 'about 6' deep inside a stand at D/h = 0.125 (+-0.1 for 'about')")
    rough = r["methods"]["roughness"]
    m_back = rough["interior"]["moment_per_uh2_Nm_s2_m2"] * rough["interior"]["uh_crit_m_s"] ** 2
    check("roughness moment at its u_h,crit / M_crit", m_back / min(cm["breakage_Nm"], cm["overturning_Nm"]),
          1 - 1e-12, 1 + 1e-12, "the inversion's round trip (to rounding)")
    check("edge u_h,crit < interior u_h,crit, both methods (1 = yes)",
          1.0 if (rough["edge"]["uh_crit_m_s"] < rough["interior"]["uh_crit_m_s"]
                  and r["methods"]["single_tree"]["edge"]["uh_crit_m_s"] < single["uh_crit_m_s"]) else 0.0,
          1, 1, "an edge tree's peak moments are several times an interior tree's (Gardiner et al. 1997)")
    out.write(f"self-test: {sum(checks)} of {len(checks)} passed\n")
    return all(checks)


# ---- command line ------------------------------------------------------------------------------------------

def read_csv(path):
    with open(path, newline="") as f:
        reader = csv.reader(f)
        rows = [(reader.line_num, row) for row in reader if row and any(cell.strip() for cell in row)
                and not row[0].lstrip().startswith("#")]
    if not rows:
        raise InputError(f"{path}: no trees")
    if rows[0][1][0].strip().lower() == "species":
        header = [c.strip().lower() for c in rows[0][1]]
        missing = [c for c in CSV_COLUMNS[:4] if c not in header]
        if missing:
            raise InputError(f"{path}:{rows[0][0]}: the header lacks {', '.join(missing)}")
        body = rows[1:]
    else:
        header, body = CSV_COLUMNS, rows
    trees = []
    for n, row in body:
        if len(row) > len(header):
            raise InputError(f"{path}:{n}: {len(row)} fields, at most {len(header)} expected")
        try:
            tree = normalise_tree(dict(zip(header, (c.strip() for c in row))))
        except InputError as e:
            raise InputError(f"{path}:{n}: {e}") from None
        tree["label"] = f"{path}:{n}"
        trees.append(tree)
    return trees


def build_parser():
    p = argparse.ArgumentParser(description="ForestGALES's critical wind speeds (single-tree and roughness "
                                            "methods) from the published equations.")
    p.add_argument("--trees", metavar="FILE.csv", help="trees from a CSV file (see the module's docstring)")
    p.add_argument("--tree", action="append", default=[],
                   metavar="SPECIES,H,DBH,SPACING[,CD,CW,SOIL,ROOTING]",
                   help="a tree on the command line, the CSV's column order; may repeat")
    p.add_argument("--json", action="store_true", help="JSON instead of the text table")
    p.add_argument("--self-test", action="store_true", help="check the worked example; exit 1 if it fails")
    p.add_argument("--lean-factor", type=float, default=LEAN_FACTOR,
                   help="ForestGALES's deflection loading factor (default 1.14, Hale et al. 2015)")
    p.add_argument("--no-lean", dest="lean_factor", action="store_const", const=1.0,
                   help="no deflection loading (lean factor 1)")
    p.add_argument("--ustar", choices=("raupach", "loglaw"), default="raupach",
                   help="u* from u_h: Raupach's u*/U_h (default) or the log profile through the canopy top")
    p.add_argument("--psi-h-sign", type=lambda s: {"+": 1, "-": -1, "1": 1, "-1": -1}[s], default=1,
                   metavar="{+,-}", help="the sign of psi_h in Raupach's z0 (default +, see the docstring)")
    p.add_argument("--stem-volume", choices=("bh-paraboloid", "paraboloid", "cone"), default="bh-paraboloid",
                   help="the stem-volume stand-in (default bh-paraboloid)")
    p.add_argument("--rho", type=float, default=RHO_AIR, help="air density, kg/m^3 (default 1.225)")
    p.add_argument("--edge-distance-h", type=float, default=0.0,
                   help="the edge tree's distance downwind of the edge, in tree heights (default 0)")
    return p


def main(argv=None):
    opts = build_parser().parse_args(argv)
    if opts.self_test:
        return 0 if self_test(opts, sys.stdout) else 1
    if not (opts.lean_factor >= 1.0 and math.isfinite(opts.lean_factor)):
        print(f"forestgales_side_by_side: --lean-factor {opts.lean_factor}: at least 1 expected",
              file=sys.stderr)
        return 2
    if not (opts.rho > 0.0 and math.isfinite(opts.rho)) or not (opts.edge_distance_h >= 0.0):
        print("forestgales_side_by_side: --rho must be positive and --edge-distance-h not negative",
              file=sys.stderr)
        return 2
    try:
        trees = []
        if opts.trees:
            trees += read_csv(opts.trees)
        for n, spec in enumerate(opts.tree, 1):
            cells = [c.strip() for c in spec.split(",")]
            if len(cells) > len(CSV_COLUMNS):
                raise InputError(f"--tree {n}: at most {len(CSV_COLUMNS)} fields")
            try:
                tree = normalise_tree(dict(zip(CSV_COLUMNS, cells)))
            except InputError as e:
                raise InputError(f"--tree {n}: {e}") from None
            tree["label"] = f"--tree {n}"
            trees.append(tree)
        if not trees:
            trees = [dict(normalise_tree(dict(t)), label=f"built-in tree {n}")
                     for n, t in enumerate(BUILT_IN, 1)]
        results = []
        for tree in trees:
            try:
                results.append(evaluate(tree, opts))
            except InputError as e:
                raise InputError(f"{tree['label']}: {e}") from None
    except (InputError, OSError) as e:
        print(f"forestgales_side_by_side: {e}", file=sys.stderr)
        return 2
    if opts.json:
        json.dump({"settings": settings_of(opts), "trees": results}, sys.stdout, indent=2)
        sys.stdout.write("\n")
    else:
        text_report(results, opts, sys.stdout)
    return 0


if __name__ == "__main__":
    sys.exit(main())
