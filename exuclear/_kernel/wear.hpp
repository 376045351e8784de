// A worn joint's surfaces and its profiles over a run (docs/physics.md section 11): the
// penetration of the worn surfaces over the contact arc, the worn contact's normal and
// penetration, the pressure and one accepted step's wear (exuclear/wear/surface.py), and the
// profiles an evaluation uses with the wear of each accepted step (WearState).  Python:
// exuclear/engine/_python_kernel/wear.py and exuclear/wear/surface.py, whose NumPy
// expressions are written here node by node over the same window, in the same order.
//
// The bearing's depth h_B(theta) [m] is kept on N nodes theta_k = 2 pi k / N of the joint
// frame, measured radially from the bearing's centre; the journal's h_J(phi) on N nodes of its
// own frame, measured along its radius.  The journal's centre sits at e = (ex, ey) from the
// bearing's centre, turned by psi about the axis.

#pragma once

#include <cstdio>

#include "laws.hpp"

namespace {

// ---- surface.py: the grid and its interpolation ---------------------------------------------
struct Grid {  // surface.py Grid: the profile nodes, their cosine and sine, the spacing
    int n = 0;
    std::vector<double> theta, cos, sin;
    double dtheta = 0.0;
};

Grid grid(int nodes) {
    Grid g;
    g.n = nodes;
    g.theta.resize(static_cast<size_t>(nodes));
    g.cos.resize(static_cast<size_t>(nodes));
    g.sin.resize(static_cast<size_t>(nodes));
    for (int k = 0; k < nodes; ++k) {
        double theta = 2.0 * M_PI * k / nodes;
        g.theta[static_cast<size_t>(k)] = theta;
        g.cos[static_cast<size_t>(k)] = std::cos(theta);
        g.sin[static_cast<size_t>(k)] = std::sin(theta);
    }
    g.dtheta = 2.0 * M_PI / nodes;
    return g;
}

// NumPy's np.mod of floats (npy_remainder): fmod, moved to the divisor's sign, +0 for a zero
double np_mod(double a, double b) {
    double mod = std::fmod(a, b);
    if (mod != 0.0) {
        if ((b < 0.0) != (mod < 0.0)) mod += b;
    } else {
        mod = std::copysign(0.0, b);
    }
    return mod;
}

// NumPy's np.maximum of floats: a where a >= b or a is NaN, else b
double np_maximum(double a, double b) { return (a >= b || std::isnan(a)) ? a : b; }

// surface.py periodic_value: values on the nodes k dtheta interpolated linearly at angle [rad] (any range)
double periodic_value(const std::vector<double>& values, double angle, double dtheta) {
    long n = static_cast<long>(values.size());
    double x = np_mod(angle / dtheta, static_cast<double>(n));
    double fl = std::floor(x);
    long k = static_cast<long>(fl) % n;
    double f = x - fl;
    return (1.0 - f) * values[static_cast<size_t>(k)] + f * values[static_cast<size_t>((k + 1) % n)];
}

// surface.py WINDOW_MARGIN: nodes added on each side of the arc where the surfaces can overlap
const int WINDOW_MARGIN = 3;

// surface.py window: the nodes where the worn surfaces can overlap, and WINDOW_MARGIN more on
// each side: wear only deepens the bearing and thins the journal, so an overlap needs that of
// the unworn circles, |e| cos(theta - alpha) > c about the eccentricity's angle alpha (eq. (72)).
// Without one, the nodes about alpha.  Into `nodes`, in NumPy's order (centre - m ... centre + m).
void window(std::vector<int>& nodes, const Grid& g, double ex, double ey, double clearance) {
    double ecc = std::sqrt(ex * ex + ey * ey);
    // Python's round() rounds half to even, as nearbyint does in the default rounding mode
    long centre = static_cast<long>(std::nearbyint(std::atan2(ey, ex) / g.dtheta));
    double ratio = clearance / ecc;
    double half = ecc > 0.0 ? std::acos(1.0 < ratio ? 1.0 : ratio) : 0.0;
    long m = static_cast<long>(half / g.dtheta) + 1 + WINDOW_MARGIN;
    if (g.n / 2 < m) m = g.n / 2;
    nodes.resize(static_cast<size_t>(2 * m + 1));
    for (long i = -m; i <= m; ++i) {
        long k = (centre + i) % g.n;  // Python's modulo: never negative
        nodes[static_cast<size_t>(i + m)] = static_cast<int>(k < 0 ? k + g.n : k);
    }
}

// surface.py SurfaceField: the two surfaces along the rays of the window's nodes (eqs.
// (72)-(74)): w the penetration [m] along the journal's normal (> 0: overlap), (nx, ny) that
// normal, cos_gamma its cosine to the ray, area the bearing's surface element [m^2].
struct SurfaceField {
    std::vector<int> nodes;
    std::vector<double> w, nx, ny, cos_gamma, area;
};

// surface.py surface_field: along the ray n_k from the bearing's centre the unworn journal's
// surface is at rho = e . n_k + sqrt(R_J^2 - (e x n_k)^2) (eq. (72)); its normal there makes
// the angle gamma with the ray, cos gamma = sqrt(R_J^2 - (e x n_k)^2) / R_J.  The radial
// overlap rho - R_B - h_B times cos gamma is the overlap along the normal; the journal's
// depth, along its own normal, comes off it (eq. (73)).  journal: null where it does not wear.
void surface_field(SurfaceField& f, const Grid& g, double r_j, double r_b, double length, double ex, double ey,
                   double psi, const std::vector<double>& bearing, const std::vector<double>* journal) {
    window(f.nodes, g, ex, ey, r_b - r_j);
    size_t m = f.nodes.size();
    f.w.resize(m);
    f.nx.resize(m);
    f.ny.resize(m);
    f.cos_gamma.resize(m);
    f.area.resize(m);
    for (size_t i = 0; i < m; ++i) {
        size_t k = static_cast<size_t>(f.nodes[i]);
        double cos_t = g.cos[k], sin_t = g.sin[k], depth = bearing[k];
        double a = ex * cos_t + ey * sin_t;
        double b = std::sqrt(np_maximum(r_j * r_j - (ex * ex + ey * ey) + a * a, 0.0));
        double rho = a + b;
        f.nx[i] = (rho * cos_t - ex) / r_j;
        f.ny[i] = (rho * sin_t - ey) / r_j;
        f.cos_gamma[i] = b / r_j;
        double w = (rho - r_b - depth) * f.cos_gamma[i];                                // eq. (73)
        if (journal != nullptr) {
            w = w - periodic_value(*journal, std::atan2(f.ny[i], f.nx[i]) - psi, g.dtheta);
        }
        f.w[i] = w;
        f.area[i] = length * (r_b + depth) * g.dtheta / np_maximum(f.cos_gamma[i], 1e-12);  // eq. (74)
    }
}

// surface.py overlap_at: the overlap along the journal's normal (eq. (73)) on the ray at angle
// [rad], the profiles interpolated linearly between their nodes
double overlap_at(const Grid& g, double r_j, double r_b, double ex, double ey, double psi, double angle,
                  const std::vector<double>& bearing, const std::vector<double>* journal) {
    double cos_t = std::cos(angle), sin_t = std::sin(angle);
    double a = ex * cos_t + ey * sin_t;
    double b = std::sqrt(np_maximum(r_j * r_j - (ex * ex + ey * ey) + a * a, 0.0));
    double rho = a + b;
    double w = (rho - r_b - periodic_value(bearing, angle, g.dtheta)) * b / r_j;
    if (journal != nullptr) {
        double phi = std::atan2(rho * sin_t - ey, rho * cos_t - ex) - psi;
        w -= periodic_value(*journal, phi, g.dtheta);
    }
    return w;
}

struct WornContact {  // surface.py WornContact: the penetration the law takes, the unit normal
    double delta, nx, ny;
};

// surface.py surface_field and worn_contact's resultant in one pass over the window, for the
// force evaluations: a node whose surfaces do not overlap adds nothing to the resultant of
// eq. (75) (its term is an exact zero), so its normal and area are not computed, and nothing
// is stored.  The resultant's sums are those of worn_contact over surface_field, node by
// node in the same order: the same bits.
void overlap_resultant(std::vector<int>& nodes, const Grid& g, double r_j, double r_b, double length, double ex,
                       double ey, double psi, const std::vector<double>& bearing, const std::vector<double>* journal,
                       double& rx, double& ry) {
    window(nodes, g, ex, ey, r_b - r_j);
    rx = 0.0;
    ry = 0.0;
    double e2 = ex * ex + ey * ey;
    for (int node : nodes) {
        size_t k = static_cast<size_t>(node);
        double cos_t = g.cos[k], sin_t = g.sin[k], depth = bearing[k];
        double a = ex * cos_t + ey * sin_t;
        double b = std::sqrt(np_maximum(r_j * r_j - e2 + a * a, 0.0));
        double rho = a + b;
        double cos_gamma = b / r_j;
        double w = (rho - r_b - depth) * cos_gamma;                                      // eq. (73)
        double nx = 0.0, ny = 0.0;
        if (journal != nullptr) {
            nx = (rho * cos_t - ex) / r_j;
            ny = (rho * sin_t - ey) / r_j;
            w = w - periodic_value(*journal, std::atan2(ny, nx) - psi, g.dtheta);
        }
        if (!(w > 0.0)) continue;
        if (journal == nullptr) {
            nx = (rho * cos_t - ex) / r_j;
            ny = (rho * sin_t - ey) / r_j;
        }
        double q = w * (length * (r_b + depth) * g.dtheta / np_maximum(cos_gamma, 1e-12));  // eq. (74)
        rx += q * nx;
        ry += q * ny;
    }
}

// surface.py worn_contact: the normal is that of the resultant sum w_k+ n_k A_k of the
// overlaps (eq. (75)), the eccentricity's direction where the surfaces do not overlap; the
// penetration is the overlap on the ray along that normal (eq. (76)).  Both move
// continuously with the journal, as Newton's iterations on the contact force need.
WornContact worn_contact(std::vector<int>& nodes, const Grid& g, double r_j, double r_b, double length, double ex,
                         double ey, double psi, const std::vector<double>& bearing, const std::vector<double>* journal) {
    double rx, ry;
    overlap_resultant(nodes, g, r_j, r_b, length, ex, ey, psi, bearing, journal, rx, ry);
    double r = std::sqrt(rx * rx + ry * ry);
    WornContact c;
    if (r > 0.0) {
        c.nx = rx / r;
        c.ny = ry / r;
    } else {
        double ecc = std::sqrt(ex * ex + ey * ey);
        c.nx = ecc > 0.0 ? ex / ecc : 1.0;
        c.ny = ecc > 0.0 ? ey / ecc : 0.0;
    }
    c.delta = overlap_at(g, r_j, r_b, ex, ey, psi, std::atan2(c.ny, c.nx), bearing, journal);
    return c;
}

// surface.py hertz_half_width: the half-width a [m] of the Hertz strip of a journal in a
// bearing (eq. (78)): a = sqrt(4 F_N R* / (pi L E*)) with R* = R_J R_B / (R_B - R_J)
double hertz_half_width(double f_n, double r_j, double r_b, double length, double e_star) {
    double r_star = r_j * r_b / (r_b - r_j);
    return std::sqrt(4.0 * f_n * r_star / (M_PI * length * e_star));
}

// surface.py pressure_shape: the pressure's shape over the window's nodes, up to its scale:
// the overlap w+ (WEAR_WINKLER, eq. (77)) or sqrt(1 - (s / a)^2) at the arc length s from the
// normal's node (WEAR_HERTZ, eq. (78)); at least the deepest node carries load.  Into q.
void pressure_shape(std::vector<double>& q, const SurfaceField& f, const Grid& g, int pressure, double normal_x,
                    double normal_y, double half_width, double r_b) {
    size_t m = f.nodes.size();
    q.resize(m);
    bool loaded = false;
    if (pressure == WEAR_WINKLER) {
        for (size_t i = 0; i < m; ++i) q[i] = np_maximum(f.w[i], 0.0);
    } else {
        double angle = std::atan2(normal_y, normal_x);
        for (size_t i = 0; i < m; ++i) {
            double s = r_b * (np_mod(g.theta[static_cast<size_t>(f.nodes[i])] - angle + M_PI, 2.0 * M_PI) - M_PI);
            double x = s / half_width;
            q[i] = std::sqrt(np_maximum(1.0 - x * x, 0.0));  // NumPy's ** 2 is the square x * x
        }
    }
    for (size_t i = 0; i < m; ++i) loaded = loaded || q[i] > 0.0;
    if (!loaded) {  // the deepest node (NumPy's argmax: the first of equals)
        size_t deepest = 0;
        for (size_t i = 1; i < m; ++i) {
            if (f.w[i] > f.w[deepest]) deepest = i;
        }
        std::fill(q.begin(), q.end(), 0.0);
        q[deepest] = 1.0;
    }
}

// surface.py WearStep: one accepted step's wear, the depth added to the bearing's and the
// journal's nodes [m] (all nodes), the pressure on every node (> 0: the bearing's node is in
// contact), and the step's stability number k_D K ds (eq. (81)).
struct WearStep {
    std::vector<double> bearing, journal, p;
    double stability = 0.0;
};

// surface.py wear_step: the wear of one accepted step (eqs. (77), (79), (80)).  The pressure
// p_k = F_N q_k / |sum q_j n_j A_j| has the contact law's F_N as its resultant; each surface
// loses k_D p ds along its normal, ds = slip the relative slip of the step [m].  The bearing's
// radial depth grows by that over cos gamma; the journal's node at phi takes the pressure at
// its own point.  modulus_factor: the law's exponent d ln F / d ln delta for the Winkler
// modulus K of eq. (81) (0: no bound, the Hertz strip).
void wear_step(WearStep& out, const SurfaceField& f, const Grid& g, const std::vector<double>& q, double f_n,
               double slip, double coefficient, bool wears_bearing, bool wears_journal, double psi, double ex,
               double ey, double r_j, double modulus_factor) {
    size_t m = f.nodes.size(), n = static_cast<size_t>(g.n);
    double rx = 0.0, ry = 0.0;
    for (size_t i = 0; i < m; ++i) {
        double qa = q[i] * f.area[i];
        rx += qa * f.nx[i];
        ry += qa * f.ny[i];
    }
    double scale = f_n / std::sqrt(rx * rx + ry * ry);
    out.p.assign(n, 0.0);
    for (size_t i = 0; i < m; ++i) out.p[static_cast<size_t>(f.nodes[i])] = scale * q[i];
    out.bearing.assign(n, 0.0);
    out.journal.assign(n, 0.0);
    if (wears_bearing) {
        for (size_t i = 0; i < m; ++i) {
            size_t k = static_cast<size_t>(f.nodes[i]);
            out.bearing[k] = coefficient * slip * out.p[k] / f.cos_gamma[i];
        }
    }
    if (wears_journal) {
        for (size_t k = 0; k < n; ++k) {
            double phi = g.theta[k] + psi;  // the journal's nodes, in the joint frame
            double qx = ex + r_j * std::cos(phi), qy = ey + r_j * std::sin(phi);
            out.journal[k] = coefficient * slip * periodic_value(out.p, std::atan2(qy, qx), g.dtheta);
        }
    }
    out.stability = coefficient * modulus_factor * scale * slip;
}

// ---- _python_kernel/wear.py ------------------------------------------------------------------
// An accepted step's stability number k_D K ds (eq. (81)) above which the profile's update
// overshoots (its error changes sign each step; above 2 it grows).
const double STABILITY_LIMIT = 1.0;
// wear.py CONFORMAL_DEPTH: a worn contact is conformal (the joint asks for a Jacobian per step)
// where the profiles are deeper than this share of the contact's penetration.
const double CONFORMAL_DEPTH = 0.1;
// The relative change of the penetration for the law's exponent d ln F / d ln delta.
const double EXPONENT_STEP = 1e-3;

// wear.py Profiles: the two depth profiles [m], the slip each bearing node has seen in contact
// [m] and its sum of stability numbers; worn: some depth > 0 (the contact is the worn one).
struct Profiles {
    std::vector<double> bearing, journal, slip, stability;
    bool worn = false;
    double deepest = 0.0;  // the largest depth of the two profiles [m]

    void update_worn() {
        deepest = 0.0;
        for (double d : bearing) deepest = d > deepest ? d : deepest;
        for (double d : journal) deepest = d > deepest ? d : deepest;
        worn = deepest > 0.0;
    }
};

// wear.py WearState: a planar joint's wear, or one slice's of a spatial joint (on the slice's
// length L / N with its share of the law's force, in its plane: section 11.7).  As the contact
// history, the profiles are kept at the start (previous) and at the end (current) of the last
// accepted step: an evaluation of a new step uses current, one of a step computed again
// previous, and a run's first evaluation the initial profiles (exuclear.Wear's bearing and
// journal), set by the binding set_wear.
struct WearState {
    Grid grid;            // n = 0: the joint does not wear
    double e_star = 0.0;  // E* [Pa] of the law, for the Hertz strip's half-width
    double length = 0.0;  // the length [m] the profiles stand for: L, a slice's L / N
    Profiles initial, previous, current;
    double last_stability = 0.0;  // the last accepted step's k_D K ds
    // scratch, storage reused (no allocation per evaluation)
    SurfaceField field;
    std::vector<double> q;
    WearStep step;
    Profiles next;

    void reset() {
        previous = initial;
        current = initial;
        last_stability = 0.0;
    }

    // WearState.field: the surfaces of `profiles` at the eccentricity (ex, ey) and the turn psi
    void field_of(const Params& a, const Profiles& profiles, double ex, double ey, double psi) {
        const std::vector<double>* journal = a.wear_surface != WEAR_BEARING ? &profiles.journal : nullptr;
        surface_field(field, grid, a.r_j, a.r_b, length, ex, ey, psi, profiles.bearing, journal);
    }

    // WearState.kinematics: the contact of the worn surfaces (eqs. (75), (76)) in place of the
    // circles' kin; the circles' own where nothing has worn yet (bit for bit the unworn joint)
    Kinematics kinematics(const Params& a, const Profiles& profiles, const Kinematics& kin, double psi, double dvx,
                          double dvy, double omega_i, double omega_j) {
        if (!profiles.worn) return kin;
        const std::vector<double>* journal = a.wear_surface != WEAR_BEARING ? &profiles.journal : nullptr;
        WornContact c = worn_contact(field.nodes, grid, a.r_j, a.r_b, length, kin.ex, kin.ey, psi, profiles.bearing,
                                     journal);
        return kinematics_along(a.r_j, a.r_b, kin.ex, kin.ey, c.delta + (a.r_b - a.r_j), c.nx, c.ny, dvx, dvy, omega_i,
                                omega_j);
    }

    // WearState.slice_kinematics: a spatial slice's contact of the worn surfaces in its plane
    // (eqs. (75), (76) at its eccentricity, eq. (35)), the rest of its kinematics along that
    // normal (eqs. (36)-(40)); the unworn slice's own kin where nothing has worn yet
    Kinematics slice_kinematics(const Params& a, const Profiles& profiles, const Kinematics& kin, double psi,
                                const V3& p, const V3& u, const V3& dv, const V3& dw, const V3& w_j) {
        if (!profiles.worn) return kin;
        const std::vector<double>* journal = a.wear_surface != WEAR_BEARING ? &profiles.journal : nullptr;
        WornContact c = worn_contact(field.nodes, grid, a.r_j, a.r_b, length, kin.ex, kin.ey, psi, profiles.bearing,
                                     journal);
        return slice_kinematics_along(a.r_j, a.r_b, kin.s, kin.ex, kin.ey, c.delta + (a.r_b - a.r_j), c.nx, c.ny, p, u,
                                      dv, dw, w_j);
    }

    // WearState.exponent: the law's d ln F / d ln delta at delta (no rate), for the Winkler
    // modulus, by a central difference through the law's normal force (ContactLaw.normal_force
    // at delta_dot 0, v0 1: eq. (9) of the elastic force alone)
    double exponent(const Params& a, double delta) const {
        double up = delta * (1.0 + EXPONENT_STEP), down = delta * (1.0 - EXPONENT_STEP);
        double hi = up <= 0.0 ? 0.0 : damped_normal_force(elastic_force(a, up), a.damping_factor, a.v_min, 0.0, 1.0);
        double lo = down <= 0.0 ? 0.0 : damped_normal_force(elastic_force(a, down), a.damping_factor, a.v_min, 0.0, 1.0);
        return std::log(hi / lo) / std::log((1.0 + EXPONENT_STEP) / (1.0 - EXPONENT_STEP));
    }

    // WearState.accept: into `out`, the profiles after an accepted step that ends in the state
    // kin with the normal force f_n (a slice's: its share), from the profiles `base` at its
    // start; slip [m] the step's slip at the contact (|v_t| h; a slice's |v_s| h, eq. (42))
    void accept(const Params& a, const Profiles& base, Profiles& out, const Kinematics& kin, double psi, double f_n,
                double slip) {
        last_stability = 0.0;
        out = base;
        if (f_n <= 0.0 || slip <= 0.0) return;
        field_of(a, base, kin.ex, kin.ey, psi);
        bool winkler = a.wear_pressure == WEAR_WINKLER;
        double half_width = winkler ? 0.0 : hertz_half_width(f_n, a.r_j, a.r_b, length, e_star);
        pressure_shape(q, field, grid, a.wear_pressure, kin.nx, kin.ny, half_width, a.r_b);
        double factor = winkler && kin.delta > 0.0 ? exponent(a, kin.delta) : 0.0;
        wear_step(step, field, grid, q, f_n, slip, a.wear_coefficient, a.wear_surface != WEAR_JOURNAL,
                  a.wear_surface != WEAR_BEARING, psi, kin.ex, kin.ey, a.r_j, factor);
        last_stability = step.stability;
        for (size_t k = 0; k < out.bearing.size(); ++k) {  // Profiles.plus, loaded = p > 0
            double loaded = step.p[k] > 0.0 ? 1.0 : 0.0;
            out.bearing[k] = base.bearing[k] + step.bearing[k];
            out.journal[k] = base.journal[k] + step.journal[k];
            out.slip[k] = base.slip[k] + slip * loaded;
            out.stability[k] = base.stability[k] + step.stability * loaded;
        }
        out.update_worn();
    }

    // WearState.unstable: why the last accepted step (slip [m] in h [s]) was too long for the
    // profile's update, or ""; where names the slice (" of slice k"; the planar joint: "")
    std::string unstable(double slip, double h, const std::string& where) const {
        double stability = last_stability;
        if (stability <= STABILITY_LIMIT) return "";
        double longest = h * STABILITY_LIMIT / stability;
        char text[512];
        std::snprintf(text, sizeof text,
                      "the wear update is unstable: k_D K ds = %.3g > %g in one step%s (slip %.3g m in %.3g s; "
                      "docs/physics.md eq. (81)); give a step of at most %.3g s "
                      "(simulationSettings.timeIntegration.maxStepSize) or a smaller wear coefficient",
                      stability, STABILITY_LIMIT, where.c_str(), slip, h, longest);
        return text;
    }
};

}  // namespace
