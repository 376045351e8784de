// Compiled kernel of the exuclear clearance joint.
//
// The same formulas as the Python statement of the physics, in the same order and with
// the same names, so that the two can be read side by side and agree to round-off:
//   contact kinematics  exuclear/spatial.py    (docs/physics.md eqs. (33)-(40), (48)-(51); the
//                                               planar joint's eqs. (1)-(8) as one slice)
//   normal force        exuclear/contact.py    (eq. (9) once, damped_normal_force; eqs. (10)-(17))
//   friction            exuclear/friction.py   (eqs. (20)-(23))
//   one contact         exuclear/engine/_python_kernel.py Contact (response: onset velocity,
//                       normal force, friction; the same for slices and end faces)
//   loads               exuclear/spatial.py    (eqs. (41)-(45), (54))
//   contact history     exuclear/history.py    (onset velocity, records)
//   film                exuclear/film.py       (eqs. (55)-(70))
//   the joint           exuclear/engine/_python_kernel.py JointKernel (which history an
//                       evaluation uses; force and post-Newton drivers over the contacts)
// The planar joint is the spatial joint with one slice and no end faces, whose motion is
// projected on the plane normal to the bearing axis.
//
// Exudyn calls these functions through raw function pointers, without Python, when they
// are bound by pybind11, capture nothing and have exactly Exudyn's signature
// (see exuclear/engine/kernel.py, which checks that at import).
// Parameters reach the functions through the connector's `stiffness` matrix (layout in
// exuclear/engine/layout.py); the per-joint dynamic state lives in a table indexed by the
// joint id stored there.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <string>
#include <vector>

class MainSystem;  // Exudyn's; only its name enters the signatures, it is never dereferenced

namespace pybind11 {
namespace detail {
// Lets pybind11 bind functions that take Exudyn's MainSystem, which this module does not
// know.  A call from Python (the self-test's fallback check) passes any object; the
// functions never touch it.
template <> class type_caster<MainSystem> {
public:
    bool load(handle src, bool) {
        ptr_ = reinterpret_cast<MainSystem*>(src.ptr());
        return true;
    }
    static constexpr auto name = const_name("exudyn.MainSystem");
    template <typename T> using cast_op_type = MainSystem&;
    operator MainSystem&() { return *ptr_; }
    static handle cast(const MainSystem&, return_value_policy, handle) { return none().release(); }

private:
    MainSystem* ptr_ = nullptr;
};
}  // namespace detail
}  // namespace pybind11

namespace py = pybind11;

using V3 = std::array<double, 3>;
using V6 = std::array<double, 6>;
using M3 = std::array<V3, 3>;
using M6 = std::array<V6, 6>;
using StdVector = std::vector<double>;

namespace {

const double INF = std::numeric_limits<double>::infinity();

// ---- parameters: the named layout (exuclear/engine/layout.py LAYOUT) ----------------------
enum Role { MAIN = 0, PROBE = 1, TORQUE = 2 };
enum FrictionCode { FRICTION_NONE = 0, FRICTION_COULOMB = 1, FRICTION_MODIFIED_COULOMB = 2 };
// layout.py FILM_CODES
enum FilmCode { FILM_NONE = 0, FILM_SHORT = 1, FILM_LONG = 2, FILM_FINITE = 3 };

// The fields of the connector's `stiffness` matrix, in the order of layout.py's LAYOUT; a
// test compares this table (exported as the module's LAYOUT) with layout.py's.
enum Field {
    JOINT_ID, ROLE, TOKEN, JOURNAL_RADIUS, BEARING_RADIUS, MAX_PENETRATION,
    IMPACT_STEP, STIFFNESS_CODE, DAMPING_FACTOR, V_MIN, FRICTION_CODE,
    STIFFNESS_CONSTANTS, FRICTION_CONSTANTS,
    SLICES, LENGTH, AXIS_JOURNAL,
    AXIAL_CLEARANCE, FRICTION_RADIUS, FACE_STIFFNESS,
    FILM_MODEL, VISCOSITY, EPS_FILM, EPS_CAP,
    RATE_LIMIT, BEARING_MOTION,
    N_FIELDS
};

struct FieldPosition {
    const char* name;
    int row, column, size;
};

constexpr FieldPosition LAYOUT[N_FIELDS] = {
    {"joint_id", 0, 0, 1},        {"role", 0, 1, 1},           {"token", 0, 2, 1},
    {"journal_radius", 0, 3, 1},  {"bearing_radius", 0, 4, 1}, {"max_penetration", 0, 5, 1},
    {"impact_step", 1, 0, 1},     {"stiffness_code", 1, 1, 1}, {"damping_factor", 1, 2, 1},
    {"v_min", 1, 3, 1},           {"friction_code", 1, 4, 1},
    {"stiffness_constants", 2, 0, 6},
    {"friction_constants", 3, 0, 4},
    {"slices", 4, 0, 1},          {"length", 4, 1, 1},         {"axis_journal", 4, 2, 3},
    {"axial_clearance", 5, 0, 1}, {"friction_radius", 5, 1, 1}, {"face_stiffness", 5, 2, 1},
    {"film_model", 3, 4, 1},      {"viscosity", 3, 5, 1},
    {"eps_film", 5, 4, 1},        {"eps_cap", 5, 5, 1},
    {"rate_limit", 1, 5, 1},      {"bearing_motion", 4, 5, 1},
};

double field(const M6& p, Field f, int i = 0) { return p[LAYOUT[f].row][LAYOUT[f].column + i]; }

struct Params {
    long id;
    int role;
    double r_j, r_b, max_penetration, impact_step;
    int stiffness_code;
    double damping_factor, v_min;
    int friction_code;
    double kp[6];
    double fp[4];
    int slices;  // 0: the planar joint (one slice, the motion projected on the plane normal to the axis)
    double length;
    V3 axis_journal;
    // the spatial joint's axial clearance (section 9.6): total play (0: none), friction radius
    // R_e, face stiffness K_f
    double play, friction_radius, face_stiffness;
    // the lubricated joint's film (section 10): model code (0: dry), viscosity, blend thresholds (eq. (70))
    int film_model;
    double viscosity, eps_film, eps_cap;
    double rate_limit;  // KAPPA of the joint's own step control (0: off)
    bool bearing_motion;  // the loads use the bearing's spin (layout.py uses_bearing_motion); false: taken as 0
};

Params decode(const M6& p) {  // every field but the token (which only the Python handle reads)
    Params a;
    a.id = static_cast<long>(field(p, JOINT_ID));
    a.role = static_cast<int>(field(p, ROLE));
    a.r_j = field(p, JOURNAL_RADIUS);
    a.r_b = field(p, BEARING_RADIUS);
    a.max_penetration = field(p, MAX_PENETRATION);
    a.impact_step = field(p, IMPACT_STEP);
    a.stiffness_code = static_cast<int>(field(p, STIFFNESS_CODE));
    a.damping_factor = field(p, DAMPING_FACTOR);
    a.v_min = field(p, V_MIN);
    a.friction_code = static_cast<int>(field(p, FRICTION_CODE));
    for (int i = 0; i < LAYOUT[STIFFNESS_CONSTANTS].size; ++i) a.kp[i] = field(p, STIFFNESS_CONSTANTS, i);
    for (int i = 0; i < LAYOUT[FRICTION_CONSTANTS].size; ++i) a.fp[i] = field(p, FRICTION_CONSTANTS, i);
    a.slices = static_cast<int>(field(p, SLICES));
    a.length = field(p, LENGTH);
    a.axis_journal = V3{field(p, AXIS_JOURNAL, 0), field(p, AXIS_JOURNAL, 1), field(p, AXIS_JOURNAL, 2)};
    a.play = field(p, AXIAL_CLEARANCE);
    a.friction_radius = field(p, FRICTION_RADIUS);
    a.face_stiffness = field(p, FACE_STIFFNESS);
    a.film_model = static_cast<int>(field(p, FILM_MODEL));
    a.viscosity = field(p, VISCOSITY);
    a.eps_film = field(p, EPS_FILM);
    a.eps_cap = field(p, EPS_CAP);
    a.rate_limit = field(p, RATE_LIMIT);
    a.bearing_motion = field(p, BEARING_MOTION) != 0.0;
    return a;
}

// ---- physics: geometry.py and spatial.py (docs/physics.md eqs. (1)-(8), (33)-(40), (48)-(51)) --
V3 cross(const V3& a, const V3& b) {
    return V3{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

double slice_centre(double length, int slices, int k) {  // eq. (33): the centre of slice k
    double width = length / slices;
    return -0.5 * length + (k + 0.5) * width;
}

V3 journal_axis(const V3& angles, const V3& axis_journal) {  // eq. (34): Rx(a) Ry(b) Rz(c) a_J
    double ca = std::cos(angles[0]), sa = std::sin(angles[0]);
    double cb = std::cos(angles[1]), sb = std::sin(angles[1]);
    double cc = std::cos(angles[2]), sc = std::sin(angles[2]);
    V3 r0{cb * cc, -cb * sc, sb};
    V3 r1{ca * sc + sa * sb * cc, ca * cc - sa * sb * sc, -sa * cb};
    V3 r2{sa * sc - ca * sb * cc, sa * cc + ca * sb * sc, ca * cb};
    return V3{dot(r0, axis_journal), dot(r1, axis_journal), dot(r2, axis_journal)};
}

// One contact's kinematics: spatial.py's SliceKinematics (side 0) or FaceKinematics (side -1, +1).
struct Kinematics {
    int side;
    double s, ex, ey, ecc, nx, ny, a, delta, delta_dot, v_t, v_a, speed;
};

// geometry.py contact_kinematics, eqs. (1)-(8): the planar joint's one slice.  The spatial
// slice's eqs. (35)-(40) reduce to these for the motion projected on the plane normal to the
// axis (s = 0, m = n, w_j x p normal to n); they are evaluated in this reduced form, in both
// kernels, so that the planar joint keeps its results bit for bit (some scenes, e.g. a 3D
// double pendulum at a coarse fixed step, change course on a last-bit change of the force).
// (ex, ey) the eccentricity, (dvx, dvy) the relative velocity, omega_i, omega_j the journal's and
// the bearing's spin about the axis.
Kinematics contact_kinematics(double r_j, double r_b, double ex, double ey, double dvx, double dvy, double omega_i,
                              double omega_j) {
    Kinematics k{};
    k.side = 0;
    k.ex = ex;
    k.ey = ey;
    k.ecc = std::sqrt(ex * ex + ey * ey);
    if (k.ecc > 0.0) {
        k.nx = ex / k.ecc;
        k.ny = ey / k.ecc;
    } else {  // centred journal: no contact, any normal keeps the values finite
        k.nx = 1.0;
        k.ny = 0.0;
    }
    k.delta_dot = dvx * k.nx + dvy * k.ny;                                             // eq. (7)
    k.v_t = dvx * k.ny - dvy * k.nx - omega_i * r_j + omega_j * r_b;                   // eq. (8)
    k.delta = k.ecc - (r_b - r_j);                                                     // eq. (4)
    k.speed = std::fabs(k.v_t);
    return k;
}

// spatial.py slice_kinematics, eqs. (35)-(40)
Kinematics slice_kinematics(double r_j, double r_b, double z, const V3& p, const V3& u, const V3& dv, const V3& dw,
                            const V3& w_j) {
    Kinematics k;
    k.side = 0;
    k.s = (z - p[2]) / u[2];                                            // eq. (35)
    k.ex = p[0] + k.s * u[0];
    k.ey = p[1] + k.s * u[1];
    k.ecc = std::sqrt(k.ex * k.ex + k.ey * k.ey);
    if (k.ecc > 0.0) {
        k.nx = k.ex / k.ecc;
        k.ny = k.ey / k.ecc;
    } else {  // journal axis on the bearing axis: no contact, any normal keeps the values finite
        k.nx = 1.0;
        k.ny = 0.0;
    }
    k.delta = k.ecc - (r_b - r_j);                                      // eq. (36)
    k.a = (k.nx * u[0] + k.ny * u[1]) / u[2];                           // eq. (37)
    V3 su{k.s * u[0], k.s * u[1], k.s * u[2]};
    V3 wp = cross(w_j, p);
    V3 ws = cross(dw, su);
    V3 w{dv[0] - wp[0] + ws[0], dv[1] - wp[1] + ws[1], dv[2] - wp[2] + ws[2]};
    k.delta_dot = k.nx * w[0] + k.ny * w[1] - k.a * w[2];               // eq. (38)
    V3 r{su[0] + r_j * k.nx, su[1] + r_j * k.ny, su[2]};                // Q_J - P_J, eq. (39)
    V3 lever{k.delta * k.nx - p[0], k.delta * k.ny - p[1], -p[2]};      // Q_J - Q_B - p
    V3 wr = cross(dw, r);
    V3 wl = cross(w_j, lever);
    V3 v{dv[0] + wr[0] + wl[0], dv[1] + wr[1] + wl[1], dv[2] + wr[2] + wl[2]};
    k.v_t = v[0] * k.ny - v[1] * k.nx;                                   // eq. (40)
    k.v_a = v[2];
    k.speed = std::sqrt(k.v_t * k.v_t + k.v_a * k.v_a);
    return k;
}

const int FACE_SIDES[2] = {-1, 1};  // face 0 at z = -L/2, face 1 at z = +L/2

Kinematics face_kinematics(double length, double play, double r_e, int side, const V3& p, const V3& u, const V3& dv,
                           const V3& dw, const V3& w_j) {
    Kinematics k{};
    k.side = side;
    k.s = side * 0.5 * (length + play);                                 // eq. (48)
    double cz = p[2] + k.s * u[2];
    k.delta = 0.5 * length - side * cz;                                 // eq. (49)
    V3 su{k.s * u[0], k.s * u[1], k.s * u[2]};
    V3 wp = cross(w_j, p);
    V3 ws = cross(dw, su);
    k.delta_dot = -side * (dv[2] - wp[2] + ws[2]);                      // eq. (50)
    k.v_t = r_e * dot(dw, u);                                           // eq. (51)
    k.ex = p[0] + su[0];
    k.ey = p[1] + su[1];
    return k;
}

bool finite(const Kinematics& k) {
    return std::isfinite(k.ex) && std::isfinite(k.ey) && std::isfinite(k.delta_dot) && std::isfinite(k.v_t);
}

// ---- physics: contact.py -------------------------------------------------------------------
// Stiffness models by kernel_code; kp are their kernel_parameters() (exuclear/contact.py).
const int STIFFNESS_CODES = 7;

// _LogLineContact._solve: s with s (ln(C/s) + beta) = delta, safeguarded Newton in (0, s_peak)
double log_line_solve(double delta, double c, double beta, double rtol, int max_iter) {
    double hi = c * std::exp(beta - 1.0);
    if (delta >= hi) return std::numeric_limits<double>::quiet_NaN();  // beyond the model's largest penetration
    double lo = 0.0;
    double s = delta / (std::log(c / delta) + beta);
    if (!(lo < s && s < hi)) s = 0.5 * hi;
    for (int i = 0; i < max_iter; ++i) {
        double log_term = std::log(c / s) + beta;
        double r = s * log_term - delta;
        if (r > 0.0) hi = s; else lo = s;
        double s_new = s - r / (log_term - 1.0);
        if (!(lo < s_new && s_new < hi)) s_new = 0.5 * (lo + hi);
        if (std::fabs(s_new - s) <= rtol * s_new) return s_new;
        s = s_new;
    }
    return s;
}

double elastic_force(const Params& a, double delta) {  // F_e(delta) for delta > 0
    const double* kp = a.kp;
    switch (a.stiffness_code) {
        case 0:  // hertz point contact: K delta^n
        case 6:  // pereira: K delta^n
            return kp[0] * std::pow(delta, kp[1]);
        case 1:  // liu, eq. (11): (pi E* L / 2) sqrt(1 / (2 (c + delta))) delta^n
            return kp[0] * std::sqrt(1.0 / (2.0 * (kp[1] + delta))) * std::pow(delta, kp[2]);
        case 2:  // johnson, radzimovsky, esdu-78035, dubowsky-freudenstein: implicit line contact
        case 3:
        case 4:
        case 5:
            return kp[0] * log_line_solve(delta, kp[1], kp[2], kp[3], static_cast<int>(kp[4]));
        default:
            throw std::runtime_error("exuclear kernel: unknown stiffness code " + std::to_string(a.stiffness_code));
    }
}

// ---- physics: timescales.py ---------------------------------------------------------------
// Gauss-Legendre nodes and weights on [0, 1] (timescales.py _GAUSS_NODES, _GAUSS_WEIGHTS), in w
// with delta = delta_max w^2; and the relative tolerance of the impact's depth (_DEPTH_RTOL).
const double GAUSS_NODES[4] = {0.0694318442029737, 0.3300094782075719, 0.6699905217924281, 0.9305681557970263};
const double GAUSS_WEIGHTS[4] = {0.1739274225687269, 0.3260725774312731, 0.3260725774312731, 0.1739274225687269};
const double DEPTH_RTOL = 1e-6;
const int DEPTH_MAX_ITER = 200;  // timescales.py PENETRATION_MAX_ITER

double stored_energy(const Params& a, double delta) {  // timescales.py stored_energy: int_0^delta F_e
    double total = 0.0;
    for (int i = 0; i < 4; ++i) {
        double w = GAUSS_NODES[i];
        total += GAUSS_WEIGHTS[i] * 2.0 * w * elastic_force(a, delta * w * w);
    }
    return delta * total;
}

// timescales.py impact_duration: pi delta_max / |v|, delta_max where the stored energy equals
// m v^2 / 2 (c beyond the clearance); the caller passes a positive, finite mass and a speed != 0
double impact_duration(const Params& a, double mass, double speed) {
    double energy = 0.5 * mass * speed * speed;
    double hi = a.r_b - a.r_j;
    double depth;
    if (!(stored_energy(a, hi) > energy)) {  // NaN (beyond a line-contact law's range) counts as above
        depth = hi;
    } else {
        double lo = 0.0;
        for (int i = 0; i < DEPTH_MAX_ITER; ++i) {
            double mid = 0.5 * (lo + hi);
            double e = stored_energy(a, mid);
            if (std::isnan(e) || e >= energy) hi = mid; else lo = mid;
            if (hi - lo <= DEPTH_RTOL * hi) break;
        }
        depth = 0.5 * (lo + hi);
    }
    return M_PI * depth / std::fabs(speed);
}

// contact.py damped_normal_force, eq. (9) for delta > 0: the elastic force f_e with the
// hysteresis factor D and the onset velocity floored at v_min
double damped_normal_force(double f_e, double damping_factor, double v_min, double delta_dot, double v0) {
    double v0_eff = v0 > v_min ? v0 : v_min;
    double f = f_e * (1.0 + damping_factor * delta_dot / v0_eff);
    return f < 0.0 ? 0.0 : f;  // no adhesion; a NaN stays NaN, to be caught
}

// ---- physics: friction.py ------------------------------------------------------------------
double smooth_step(double x, double x0, double h0, double x1, double h1) {  // S(x; x0, h0, x1, h1)
    double s = (x - x0) / (x1 - x0);
    s = s < 0.0 ? 0.0 : s;  // max(s, 0), as Python's max returns the first of equals
    s = 1.0 < s ? 1.0 : s;  // min(s, 1)
    return h0 + (h1 - h0) * s * s * (3.0 - 2.0 * s);
}

double sign(double x) { return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0); }

double friction_coefficient(const Params& a, double v_t) {  // mu(v_T), eqs. (20)-(23)
    switch (a.friction_code) {
        case FRICTION_COULOMB: {  // fp = (mu, v_eps)
            double mu = a.fp[0], v_eps = a.fp[1];
            return sign(v_t) * smooth_step(std::fabs(v_t), -v_eps, -mu, v_eps, mu);
        }
        case FRICTION_MODIFIED_COULOMB: {  // fp = (mu_s, mu_d, v_s, v_d)
            double mu_s = a.fp[0], mu_d = a.fp[1], v_s = a.fp[2], v_d = a.fp[3];
            double speed = std::fabs(v_t);
            double mu = speed < v_s   ? smooth_step(speed, -v_s, -mu_s, v_s, mu_s)
                        : speed < v_d ? smooth_step(speed, v_s, mu_s, v_d, mu_d)
                                      : mu_d;
            return sign(v_t) * mu;
        }
        default:
            return 0.0;
    }
}

// ---- physics: history.py -------------------------------------------------------------------
struct History {
    double time = 0.0;
    double delta = -INF;  // -inf: no accepted state yet
    double delta_dot = 0.0;
    bool in_contact = false;
    double v0 = 0.0;
    long onsets = 0;
    long closed = 0;
    double onset_time = 0.0, peak_force = 0.0, max_penetration = 0.0;
    // outputs at this accepted state
    double f_n = 0.0, f_t = 0.0, v_t = 0.0, ex = 0.0, ey = 0.0;
    double film_fx = 0.0, film_fy = 0.0, film_torque = 0.0;  // a lubricated joint's film (set by the driver)
};

struct Record {
    double onset_time, onset_velocity, peak_force, duration, max_penetration;
};

double onset_velocity(const History& h, double delta, double delta_dot) {
    if (h.in_contact) return h.v0;
    double d0 = h.delta;
    if (d0 == -INF) return delta_dot;  // no accepted state yet: the joint starts in contact
    return h.delta_dot + (delta_dot - h.delta_dot) * d0 / (d0 - delta);
}

// ---- one contact: _python_kernel.py's Contact classes ----------------------------------------
// A joint's contacts are its slices (one for the planar joint), then its two end faces where
// it has an axial clearance.  The kind decides the stiffness, the slip friction acts against
// and where the loads go; response() is the same for all.
enum ContactKind {
    PLANAR_SLICE,  // the planar joint's one slice: the joint's law, slip v_T (eqs. (9), (20))
    SLICE,         // a spatial slice: its share w / L of the law, slip |v_s| (eqs. (41), (42))
    FACE           // an end face: flat-punch stiffness K_f, slip at the friction radius (eq. (53))
};

int slice_count(const Params& a) { return a.slices > 0 ? a.slices : 1; }

size_t contact_count(const Params& a) { return static_cast<size_t>(slice_count(a)) + (a.play > 0.0 ? 2u : 0u); }

ContactKind contact_kind(const Params& a, size_t i) {
    if (i >= static_cast<size_t>(slice_count(a))) return FACE;
    return a.slices > 0 ? SLICE : PLANAR_SLICE;
}

double law_share(const Params& a, ContactKind kind) {  // eq. (41): w / L; all of it for the planar slice, a face
    return kind == SLICE ? 1.0 / a.slices : 1.0;
}

double slip(ContactKind kind, const Kinematics& k) {  // the speed friction's coefficient takes
    return kind == SLICE ? k.speed : k.v_t;
}

struct Response {
    double f_n, f_t, v0;
};

// Contact.response: onset velocity -> normal force -> friction, for every kind of contact
Response response(const Params& a, ContactKind kind, const History& h, const Kinematics& k) {
    if (k.delta <= 0.0) return Response{0.0, 0.0, h.in_contact ? h.v0 : 0.0};
    double v0 = onset_velocity(h, k.delta, k.delta_dot);                                    // eqs. (17)-(19)
    double f_e = kind == FACE ? a.face_stiffness * k.delta : elastic_force(a, k.delta);       // eq. (52) or the law's
    double f_n = law_share(a, kind) * damped_normal_force(f_e, a.damping_factor, a.v_min, k.delta_dot, v0);  // eq. (9)
    double f_t = a.friction_code != FRICTION_NONE ? friction_coefficient(a, slip(kind, k)) * f_n : 0.0;       // eq. (20)
    return Response{f_n, f_t, v0};
}

// ContactState.accept (exuclear/history.py): the history after an accepted state (kinematics k, time t);
// a contact that ends appends its record.
History accept(const History& h, const Params& a, ContactKind kind, const Kinematics& k, double time,
               std::vector<Record>& records) {
    History n = h;
    double delta = k.delta, delta_dot = k.delta_dot;
    if (delta > 0.0) {
        if (!h.in_contact) {
            n.v0 = onset_velocity(h, delta, delta_dot);
            n.in_contact = true;
            double d0 = h.delta;
            double share = d0 != -INF ? d0 / (d0 - delta) : 0.0;
            n.onset_time = h.time + share * (time - h.time);
            n.onsets = h.onsets + 1;
            n.peak_force = 0.0;
            n.max_penetration = 0.0;
        }
    } else {
        n.in_contact = false;
        if (h.in_contact) {  // the contact ended within this step: close its record
            double share = h.delta / (h.delta - delta);
            double end = h.time + share * (time - h.time);
            records.push_back({h.onset_time, h.v0, h.peak_force, end - h.onset_time, h.max_penetration});
            n.closed = h.closed + 1;
        }
    }
    n.delta = delta;
    n.delta_dot = delta_dot;
    n.time = time;
    n.ex = k.ex;
    n.ey = k.ey;
    n.v_t = slip(kind, k);
    if (delta > 0.0) {
        Response r = response(a, kind, h, k);  // at an onset, v0 is the same interpolation as n.v0
        n.f_n = r.f_n;
        n.f_t = r.f_t;
        n.peak_force = n.f_n > n.peak_force ? n.f_n : n.peak_force;
        n.max_penetration = delta > n.max_penetration ? delta : n.max_penetration;
    } else {
        n.f_n = 0.0;
        n.f_t = 0.0;
    }
    return n;
}

// ---- loads: spatial.py (eqs. (41)-(45), (54); the planar joint's eqs. (24)-(26)) -------------
// geometry.py joint_loads, eqs. (24)-(26), as the planar slice's share of loads = [force (3),
// torque (3), correction (3)]: F = -F_i, T = -M_i, and the bearing's moment beyond T, m_j + m_i
// (the whole of it: the driver adds no p x F for the planar joint, see joint_force)
void joint_loads(double* loads, double r_j, double r_b, const Kinematics& k, double f_n, double f_t) {
    double fx = -f_n * k.nx - f_t * k.ny;                                // eq. (24)
    double fy = -f_n * k.ny + f_t * k.nx;
    double m_i = r_j * f_t;                                              // eq. (25)
    double m_j = -r_b * f_t;                                             // eq. (26)
    loads[0] += -fx;
    loads[1] += -fy;
    loads[5] += -m_i;
    loads[8] += m_j + m_i;
}

// spatial.py add_slice_loads: a slice's share of loads = [force (3), torque (3), correction (3)]
void add_slice_loads(double* loads, double r_j, const V3& u, const Kinematics& k, double f_n, double f_t,
                     double f_a) {
    V3 n_force{f_n * k.nx, f_n * k.ny, -f_n * k.a};                     // F_N m, on the bearing at c, eq. (41)
    V3 t_force{f_t * k.ny, -f_t * k.nx, f_a};                             // friction on the bearing at Q_B, eq. (42)
    V3 total{n_force[0] + t_force[0], n_force[1] + t_force[1], n_force[2] + t_force[2]};
    V3 su{k.s * u[0], k.s * u[1], k.s * u[2]};
    V3 arm = cross(su, total);
    V3 rim = cross(V3{r_j * k.nx, r_j * k.ny, 0.0}, t_force);
    V3 couple = cross(V3{k.delta * k.nx, k.delta * k.ny, 0.0}, t_force);
    for (int i = 0; i < 3; ++i) {
        loads[i] += total[i];                                           // eq. (43)
        loads[3 + i] += arm[i] + rim[i];                                // eq. (44)
        loads[6 + i] -= couple[i];                                      // eq. (45), p x F added at the end
    }
}

void add_face_loads(double* loads, double r_e, const V3& u, const Kinematics& k, double f_n, double f_t) {
    V3 total{0.0, 0.0, -k.side * f_n};                                  // on the bearing, at c_f
    V3 su{k.s * u[0], k.s * u[1], k.s * u[2]};
    V3 arm = cross(su, total);
    V3 couple{r_e * f_t * u[0], r_e * f_t * u[1], r_e * f_t * u[2]};
    for (int i = 0; i < 3; ++i) {
        loads[i] += total[i];                                           // eq. (54)
        loads[3 + i] += arm[i] + couple[i];                             // eq. (54); the correction is p x F
    }
}

// Contact.add_loads: a contact's loads from its response
void add_loads(double* loads, const Params& a, ContactKind kind, const V3& u, const Kinematics& k, const Response& r) {
    switch (kind) {
        case PLANAR_SLICE:  // eqs. (24)-(26)
            joint_loads(loads, a.r_j, a.r_b, k, r.f_n, r.f_t);
            break;
        case SLICE: {  // spatial.py friction_components: along the slip of the contact points, eq. (42)
            double f_t = 0.0, f_a = 0.0;
            if (k.speed > 0.0) {
                f_t = r.f_t * (k.v_t / k.speed);
                f_a = r.f_t * (k.v_a / k.speed);
            }
            add_slice_loads(loads, a.r_j, u, k, r.f_n, f_t, f_a);
            break;
        }
        case FACE:
            add_face_loads(loads, a.friction_radius, u, k, r.f_n, r.f_t);
            break;
    }
}

// ---- the film: film.py (docs/physics.md section 10, eqs. (55)-(70)) ------------------------------
// film.py FilmInput (_python_kernel.py): e in the bearing's joint frame, de/dt as the connector
// hands it over (the inertial derivative in that frame's components), the absolute spins.
struct FilmInput {
    double ex, ey, vx, vy, omega_journal, omega_bearing;
};

struct FilmKinematics {  // film.py FilmKinematics, eq. (56)
    double eps, eps_dot, omega_eff, nx, ny;
};

struct FilmLoad {  // film.py FilmLoad: force on the journal, moments on journal and bearing, eqs. (68)-(69)
    double fx, fy, torque_journal, torque_bearing;
};

FilmKinematics film_kinematics(const FilmInput& in, double clearance) {  // eqs. (55)-(56)
    double ecc = std::sqrt(in.ex * in.ex + in.ey * in.ey);
    double nx, ny, phi_dot;
    if (ecc > 0.0) {
        nx = in.ex / ecc;
        ny = in.ey / ecc;
        phi_dot = (in.ex * in.vy - in.ey * in.vx) / (ecc * ecc);
    } else {  // centred: the normal along de/dt, or (1, 0) at rest
        double speed = std::sqrt(in.vx * in.vx + in.vy * in.vy);
        nx = speed > 0.0 ? in.vx / speed : 1.0;
        ny = speed > 0.0 ? in.vy / speed : 0.0;
        phi_dot = 0.0;
    }
    double eps_dot = (nx * in.vx + ny * in.vy) / clearance;
    return FilmKinematics{ecc / clearance, eps_dot, in.omega_journal + in.omega_bearing - 2.0 * phi_dot, nx, ny};
}

// film.py blend_eccentricity, eq. (70): the eccentricity ratio (and rate) the film is evaluated at
void blend_eccentricity(double eps, double eps_dot, double eps_film, double eps_cap, double& eps_b,
                        double& eps_dot_b) {
    if (eps <= eps_film) {
        eps_b = eps;
        eps_dot_b = eps_dot;
        return;
    }
    double width = eps_cap - eps_film;
    double x = (eps - eps_film) / width;
    double q = std::exp(-2.0 * x);  // tanh(x) = (1 - q) / (1 + q), 1 / cosh^2(x) = 4 q / (1 + q)^2: one exp
    eps_b = eps_film + width * ((1.0 - q) / (1.0 + q));
    eps_dot_b = eps_dot * (4.0 * q / ((1.0 + q) * (1.0 + q)));
}

// ShortBearing.components, eqs. (58)-(60): the positive part of Ocvirk's pressure.  Its sign in
// gamma is a0 + a1 cos + b1 sin with a0 = 2 eps_dot eps, a1 = -2 eps_dot, b1 = rot, positive on
// one arc (phase - half, phase + half) around the phase of (a1, b1), cos(half) = -a0 / |(a1, b1)|
// (film.py ShortBearing._arc, the same steps).  The antiderivatives
// g_n, g_t of film.py are evaluated between its ends from their cosines and sines, which follow
// from (a0, a1, b1) without trigonometric calls; only the arc's length needs acos.
void short_components(const Params& a, double clearance, double eps, double eps_dot, double omega_eff, double& f_n,
                      double& f_perp) {
    double s = std::sqrt(1.0 - eps * eps);
    double rot = eps * omega_eff * s;
    double a0 = 2.0 * eps_dot * eps, a1 = -2.0 * eps_dot, b1 = rot;
    double amplitude = std::sqrt(a1 * a1 + b1 * b1);
    // the arc's ends x1 < x2 by cosine and sine, and its length
    double c1 = 1.0, s1 = 0.0, c2 = 1.0, s2 = 0.0, length = 0.0;
    if (a0 >= amplitude) {
        if (a0 > 0.0) length = 2.0 * M_PI;  // positive everywhere: the whole circle
    } else if (a0 > -amplitude) {
        double cp = a1 / amplitude, sp = b1 / amplitude;    // phase
        double ch = -a0 / amplitude;                         // cos(half)
        double sh = std::sqrt(1.0 - ch * ch);                // sin(half) >= 0
        c1 = cp * ch + sp * sh;
        s1 = sp * ch - cp * sh;
        c2 = cp * ch - sp * sh;
        s2 = sp * ch + cp * sh;
        length = 2.0 * std::acos(ch);
    }
    double d_cos = c2 - c1, d_sin = s2 - s1;
    double d_cos2 = (c2 * c2 - s2 * s2) - (c1 * c1 - s1 * s1);  // cos(2 x2) - cos(2 x1)
    double d_sin2 = 2.0 * (s2 * c2 - s1 * c1);                  // sin(2 x2) - sin(2 x1)
    // g_n: antiderivative of (rot sin - 2 eps_dot (cos - eps)) (cos - eps)
    double in_n = (rot * (-0.25 * d_cos2 + eps * d_cos)
                   - 2.0 * eps_dot * ((0.5 + eps * eps) * length + 0.25 * d_sin2 - 2.0 * eps * d_sin));
    // g_t: antiderivative of (rot sin - 2 eps_dot (cos - eps)) sin
    double in_t = rot * (0.5 * length - 0.25 * d_sin2) - 2.0 * eps_dot * (-0.25 * d_cos2 + eps * d_cos);
    double scale = a.viscosity * a.length * a.length * a.length * a.r_j / (2.0 * clearance * clearance);  // eq. (60)
    double s2_ = s * s;
    f_n = scale * in_n / (s2_ * s2_ * s);
    f_perp = scale * in_t / (s2_ * s2_);
}

// LongBearing._arc (film.py): the arc of positive pressure of the long bearing (docs/physics.md section
// 10.2, eqs. (62a)-(62c)).  Its sign in gamma is g = a0 + a1 cos + b1 sin + a2 cos 2x + b2 sin 2x (a1 =
// sigma q1 enters only through g(0) and g(pi), below), which,
// unless the squeeze sigma is 0, has exactly two zeros, both simple: one in (0, pi) and one in (pi, 2 pi)
// (g(0) = -sigma (1 - eps)^2 (4 - eps), g(pi) = sigma (1 + eps)^2 (4 + eps)).  The positive part is one
// arc: from the first zero to the second for sigma > 0 (around the smallest gap), from the second to the
// first (plus 2 pi) for sigma < 0.  With tau = tan(gamma / 2), (1 + tau^2)^2 g is the quartic
// k0 + k1 tau + ... + k4 tau^4 (eq. (62b)); the sign of g at pi/2 (or 3 pi/2) tells which quarter
// circle holds each zero, and there it is the only root in [0, 1] of the quartic in t = |tau| or
// u = 1 / |tau|, found by Halley's iteration (QuarticRoot).  A pure function of (eps, eps_dot, omega_eff).
struct Arc {
    double c1, s1, c2, s2, length;  // cos and sin of its ends gamma_1 < gamma_2, and gamma_2 - gamma_1
};

// Halley's iteration converges cubically: once a step is below ROOT_RTOL of the root, what is left is
// of the order of its cube, round-off (measured: at most 4e-16 relative).  A step that leaves the
// bracket is replaced by bisection; ROOT_ITERATIONS is far more than needed (4 on average).
const double ROOT_RTOL = 1e-6;
const int ROOT_ITERATIONS = 100;

// film.py _root_in_unit_interval: the root in [0, 1] of p = k0 + k1 x + k2 x^2 + k3 x^3 + k4 x^4, given
// p(1) = p_one of the sign opposite to k0's (or 0), from the secant's root.  One step at a time, so that
// the arc's two roots iterate side by side (independent: the processor overlaps them).
struct QuarticRoot {
    double k[5], lo, hi, x;
    bool done;
    QuarticRoot(double k0, double k1, double k2, double k3, double k4, double p_one)
        : k{k0, k1, k2, k3, k4}, lo(0.0), hi(1.0), x(p_one == 0.0 ? 1.0 : k0 / (k0 - p_one)), done(p_one == 0.0) {}
    void step() {
        double x2 = x * x;  // p, p', p'' in Estrin's order: shorter chains of dependent operations than Horner's
        double p = (k[0] + k[1] * x) + (k[2] + k[3] * x) * x2 + k[4] * (x2 * x2);
        double dp = (k[1] + 2.0 * k[2] * x) + (3.0 * k[3] + 4.0 * k[4] * x) * x2;
        double ddp = 2.0 * k[2] + (6.0 * k[3] + 12.0 * k[4] * x) * x;
        if (p == 0.0) {
            done = true;
            return;
        }
        if ((p > 0.0) == (k[0] > 0.0)) {
            lo = x;
        } else {
            hi = x;
        }
        double den = dp * dp - 0.5 * p * ddp;
        double next = den != 0.0 ? x - p * dp / den : -1.0;
        bool halley = next >= lo && next <= hi;
        if (!halley) next = 0.5 * (lo + hi);  // the step left the bracket: bisect
        double change = std::fabs(next - x);
        x = next;
        done = halley && change <= ROOT_RTOL * x;
    }
};

// film.py LongBearing._arc: the positive arc at eps, with rho = eps omega_eff s / (2 + eps^2) and the
// squeeze factor sigma = eps_dot / (2 + 3 eps^2)
Arc long_arc(double eps, double rho, double sigma) {
    if (sigma == 0.0) {  // rotation alone: g = rho sin (2 - eps^2 - eps cos), zero at 0 and pi
        if (rho > 0.0) return Arc{1.0, 0.0, -1.0, 0.0, M_PI};
        if (rho < 0.0) return Arc{-1.0, 0.0, 1.0, 0.0, M_PI};
        return Arc{1.0, 0.0, 1.0, 0.0, 0.0};  // no film pressure at all
    }
    // sign of p in gamma (eq. (62a)): rho sin (2 - eps^2 - eps cos) + sigma (q0 + q1 cos + q2 cos^2)
    double eps3 = eps * eps * eps;
    double q0 = 7.0 * eps - 2.0 * eps3, q2 = 2.0 * eps + 3.0 * eps3;
    double a0 = sigma * (q0 + 0.5 * q2), b1 = rho * (2.0 - eps * eps), a2 = 0.5 * sigma * q2, b2 = -0.5 * rho * eps;
    // eq. (62b); k0 = g(0) and k4 = g(pi) in their factored forms, whose signs are exact
    double k0 = -sigma * (1.0 - eps) * (1.0 - eps) * (4.0 - eps), k1 = 2.0 * b1 + 4.0 * b2, k2 = 2.0 * a0 - 6.0 * a2,
           k3 = 2.0 * b1 - 4.0 * b2, k4 = sigma * (1.0 + eps) * (1.0 + eps) * (4.0 + eps);
    // the zero in (0, pi): in (0, pi/2) (tau = t) where g(pi/2) has the sign of g(pi), else in [pi/2, pi) (tau = 1 / u)
    double q_plus = k0 + k1 + k2 + k3 + k4;  // 4 g(pi/2)
    bool first_t = (q_plus > 0.0) != (k0 > 0.0) && q_plus != 0.0;
    QuarticRoot first = first_t ? QuarticRoot(k0, k1, k2, k3, k4, q_plus) : QuarticRoot(k4, k3, k2, k1, k0, q_plus);
    // the zero in (pi, 2 pi): in (3 pi/2, 2 pi) (tau = -t) where g(3 pi/2) has the sign of g(pi), else in
    // (pi, 3 pi/2] (tau = -1 / u)
    double q_minus = k0 - k1 + k2 - k3 + k4;  // 4 g(3 pi/2)
    bool second_t = (q_minus > 0.0) != (k0 > 0.0) && q_minus != 0.0;
    QuarticRoot second = second_t ? QuarticRoot(k0, -k1, k2, -k3, k4, q_minus) : QuarticRoot(k4, -k3, k2, -k1, k0, q_minus);
    for (int it = 0; it < ROOT_ITERATIONS && !(first.done && second.done); ++it) {
        if (!first.done) first.step();
        if (!second.done) second.step();
    }
    // the ends from tau: cos = (1 - tau^2) / (1 + tau^2), sin = 2 tau / (1 + tau^2), gamma = 2 arctan(tau)
    double x = first.x, d = 1.0 + x * x;
    double c1 = first_t ? (1.0 - x * x) / d : (x * x - 1.0) / d, s1 = 2.0 * x / d;
    double g1 = first_t ? 2.0 * std::atan(x) : M_PI - 2.0 * std::atan(x);
    x = second.x;
    d = 1.0 + x * x;
    double c2 = second_t ? (1.0 - x * x) / d : (x * x - 1.0) / d, s2 = -2.0 * x / d;
    double g2 = second_t ? 2.0 * M_PI - 2.0 * std::atan(x) : M_PI + 2.0 * std::atan(x);
    if (sigma > 0.0) return Arc{c1, s1, c2, s2, g2 - g1};  // around pi: from the first zero to the second
    return Arc{c2, s2, c1, s1, 2.0 * M_PI - (g2 - g1)};   // around 0: from the second to the first, + 2 pi
}

// LongBearing.components, eqs. (61)-(63): Sommerfeld's pressure, its positive part
void long_components(const Params& a, double clearance, double eps, double eps_dot, double omega_eff, double& f_n,
                     double& f_perp) {
    double s = std::sqrt(1.0 - eps * eps);
    double rho = eps * omega_eff * s / (2.0 + eps * eps);
    double sigma = eps_dot / (2.0 + 3.0 * eps * eps);
    Arc arc = long_arc(eps, rho, sigma);
    // g_n, g_t of film.py between the arc's ends, from their cosines and sines (no trigonometric calls)
    double d_cos = arc.c2 - arc.c1, d_sin = arc.s2 - arc.s1;
    double d_cos2 = (arc.c2 * arc.c2 - arc.s2 * arc.s2) - (arc.c1 * arc.c1 - arc.s1 * arc.s1);  // cos(2 x2) - cos(2 x1)
    double d_sin2 = 2.0 * (arc.s2 * arc.c2 - arc.s1 * arc.c1);                                  // sin(2 x2) - sin(2 x1)
    double two_eps_dot = 2.0 * eps_dot;
    // g_n: antiderivative of rho (2 cos + eps) sin + 2 eps_dot sin^2
    double in_n = rho * (-0.5 * d_cos2 - eps * d_cos) + two_eps_dot * (0.5 * arc.length - 0.25 * d_sin2);
    // g_t: antiderivative of (cos - eps) (rho (2 cos + eps) + 2 eps_dot sin)
    double in_t = (rho * (s * s * arc.length + 0.5 * d_sin2 - eps * d_sin)
                   + two_eps_dot * (-0.25 * d_cos2 + eps * d_cos));
    double scale = 6.0 * a.viscosity * a.r_j * a.r_j * a.r_j * a.length / (clearance * clearance);  // eq. (63)
    double s2_ = s * s;
    f_n = -scale * in_n / (s2_ * s);
    f_perp = scale * in_t / (s2_ * s2_);
}

// film.py _A1 ... _A9: Butenschoen's fits (1976), polynomials in B/D, lowest power first (eqs. (64)-(66))
const double FINITE_A[9][5] = {
    {1.1642, -1.9456, 7.1161, -10.1073, 5.0141},
    {-1.000026, -0.023634, -0.4215, -0.038817, -0.090551},
    {1.152624, -0.104565, 0.0, 0.0, 0.0},
    {-2.5905, 0.798745, 0.0, 0.0, 0.0},
    {8.73393, -2.3291, 0.0, 0.0, 0.0},
    {-13.3414, 3.424337, 0.0, 0.0, 0.0},
    {6.6294, -1.591732, 0.0, 0.0, 0.0},
    {0.70038, 3.2415, -12.2486, 18.895, -9.3561},
    {-0.999935, 0.0157434, -0.74224, 0.42278, -0.368928},
};
const int FINITE_A_DEGREE[9] = {4, 4, 1, 1, 1, 1, 1, 4, 4};
// film.py SQUEEZE_TURN: how fast a rotating film turns with the squeeze (eq. (66a))
const double SQUEEZE_TURN = 1.3;

double polynomial(const double* coefficients, int degree, double x) {  // film.py _polynomial
    double r = 0.0;
    for (int k = 0; k <= degree; ++k) r += coefficients[k] * std::pow(x, k);
    return r;
}

// FiniteBearing's a1 ... a9 at B/D = L / (2 R_J), kept per joint and recomputed when L or R_J change
// (FiniteBearing.__post_init__ computes them once per law)
struct FiniteCoefficients {
    double length = -1.0, r_j = -1.0, bd = 0.0;
    double c[9] = {};
};

const FiniteCoefficients& finite_coefficients(FiniteCoefficients& k, const Params& a) {
    if (k.length != a.length || k.r_j != a.r_j) {
        k.length = a.length;
        k.r_j = a.r_j;
        k.bd = a.length / (2.0 * a.r_j);
        for (int i = 0; i < 9; ++i) k.c[i] = polynomial(FINITE_A[i], FINITE_A_DEGREE[i], k.bd);
    }
    return k;
}

// FiniteBearing.squeeze, eq. (66): So_V at x = eps approaching the wall, x = -eps leaving it
double finite_squeeze(const FiniteCoefficients& k, double x) {
    const double* c = k.c;
    double bd = k.bd;
    double one_mx = 1.0 - x * x;
    double root_mx = std::sqrt(one_mx);
    return (4.0 * bd * bd / (one_mx * one_mx * root_mx)
            * ((0.5 * M_PI - 0.5 * std::acos(x)) * (1.0 + 2.0 * x * x) + 1.5 * x * root_mx)
            * c[7] * (1.0 - x) / (-c[8] - x));
}

// FiniteBearing.turning_squeeze, eq. (66a): the approaching and leaving numbers weighted by how far
// the squeeze has turned the rotating film; smooth in eps_dot wherever the film rotates
double finite_turning_squeeze(const FiniteCoefficients& k, double eps, double eps_dot, double omega_eff) {
    double wedge = eps * std::fabs(omega_eff) * std::sqrt(1.0 - eps * eps);
    double w = 0.5 + std::atan2(2.0 * SQUEEZE_TURN * eps_dot, wedge) / M_PI;  // atan2(0, 0) = 0: no force anyway
    if (w == 1.0) return finite_squeeze(k, eps);  // approaching without rotation, or far beyond the wedge
    if (w == 0.0) return finite_squeeze(k, -eps);
    return w * finite_squeeze(k, eps) + (1.0 - w) * finite_squeeze(k, -eps);
}

// FiniteBearing.components, eqs. (64)-(67): Butenschoen's rotation and squeeze fits
void finite_components(const Params& a, const FiniteCoefficients& k, double clearance, double eps, double eps_dot,
                       double omega_eff, double& f_n, double& f_perp) {
    const double* c = k.c;
    double bd = k.bd;
    // rotation, eqs. (64)-(65)
    double one_m = 1.0 - eps * eps;
    double so = (bd * bd * eps / (2.0 * one_m * one_m) * std::sqrt(M_PI * M_PI * one_m + 16.0 * eps * eps)
                 * c[0] * (eps - 1.0) / (c[1] + eps));
    double base = std::atan2(M_PI * std::sqrt(one_m), 2.0 * eps);
    double eps2 = eps * eps;
    double beta = base * (c[2] + c[3] * eps + c[4] * eps2 + c[5] * eps2 * eps + c[6] * eps2 * eps2);
    double so_v = finite_turning_squeeze(k, eps, eps_dot, omega_eff);
    double psi = clearance / a.r_j;
    double unit = a.length * 2.0 * a.r_j * a.viscosity / (psi * psi);  // B D eta / psi^2, eq. (67)
    double f_d = so * unit * std::fabs(omega_eff);
    double sgn = omega_eff >= 0.0 ? 1.0 : -1.0;
    double f_v = so_v * unit * eps_dot;  // signed: against the squeeze
    f_n = -f_d * std::cos(beta) - f_v;
    f_perp = sgn * f_d * std::sin(beta);
}

// FilmLaw.blended_load and _assemble: the film as the joint applies it (eqs. (68)-(70))
FilmLoad film_load(const Params& a, FiniteCoefficients& finite, const FilmInput& in) {
    double clearance = a.r_b - a.r_j;
    FilmKinematics kin = film_kinematics(in, clearance);
    double eps_b, eps_dot_b;
    blend_eccentricity(kin.eps, kin.eps_dot, a.eps_film, a.eps_cap, eps_b, eps_dot_b);
    double f_n = 0.0, f_perp = 0.0;
    if (a.film_model == FILM_SHORT) {
        short_components(a, clearance, eps_b, eps_dot_b, kin.omega_eff, f_n, f_perp);
    } else if (a.film_model == FILM_LONG) {
        long_components(a, clearance, eps_b, eps_dot_b, kin.omega_eff, f_n, f_perp);
    } else if (a.film_model == FILM_FINITE) {
        finite_components(a, finite_coefficients(finite, a), clearance, eps_b, eps_dot_b, kin.omega_eff, f_n, f_perp);
    } else {
        throw std::runtime_error("exuclear kernel: unknown film model " + std::to_string(a.film_model));
    }
    double fx = f_n * kin.nx - f_perp * kin.ny;  // n turned +90 degrees is (-n_y, n_x)
    double fy = f_n * kin.ny + f_perp * kin.nx;
    // eq. (69): Couette shear over the whole circumference, and the pressure's share
    double couette = (2.0 * M_PI * a.viscosity * a.r_j * a.r_j * a.r_j * a.length * (in.omega_journal - in.omega_bearing)
                      / (clearance * std::sqrt(1.0 - eps_b * eps_b)));
    double e_cross_f = kin.eps * clearance * (kin.nx * fy - kin.ny * fx);  // with the true e: no net moment
    return FilmLoad{fx, fy, -couette - 0.5 * e_cross_f, couette - 0.5 * e_cross_f};
}

// _python_kernel.py Film.add_loads: F = -F_film on the bearing, T = -M_J, the bearing's moment beyond T
void add_film_loads(double* loads, const FilmLoad& r) {
    loads[0] += -r.fx;
    loads[1] += -r.fy;
    loads[5] += -r.torque_journal;
    loads[8] += r.torque_bearing + r.torque_journal;
}

// Film.add_slice_loads: a spatial slice's share w / L of the film (section 10.8): -F on the bearing,
// T = s u x (-F) - M_J z, the bearing's moment beyond T (before p x F) e x F + (M_B + M_J) z
void add_film_slice_loads(double* loads, double share, const V3& u, const Kinematics& k, const FilmLoad& r) {
    double w = share;
    double fx = w * r.fx, fy = w * r.fy, m_j = w * r.torque_journal, m_b = w * r.torque_bearing;
    double sx = k.s * u[0], sy = k.s * u[1], sz = k.s * u[2];
    loads[0] += -fx;
    loads[1] += -fy;
    loads[3] += sz * fy;  // (s u) x (-F), F in the plane
    loads[4] += -sz * fx;
    loads[5] += -(sx * fy - sy * fx) - m_j;
    loads[8] += (k.ex * fy - k.ey * fx) + (m_b + m_j);
}

// _python_kernel.py slice_film_input: a slice's axis point, its rate in the bearing's rotating frame
// (the w of eq. (38)), the journal's spin relative to the bearing, the bearing's 0
FilmInput slice_film_input(const Kinematics& k, const V3& p, const V3& u, const V3& dv, const V3& dw, const V3& w_j) {
    V3 su{k.s * u[0], k.s * u[1], k.s * u[2]};
    double wx = dv[0] - (w_j[1] * p[2] - w_j[2] * p[1]) + (dw[1] * su[2] - dw[2] * su[1]);
    double wy = dv[1] - (w_j[2] * p[0] - w_j[0] * p[2]) + (dw[2] * su[0] - dw[0] * su[2]);
    return FilmInput{k.ex, k.ey, wx, wy, dw[0] * u[0] + dw[1] * u[1] + dw[2] * u[2], 0.0};
}

void set_film_outputs(History& h, const FilmLoad& r, double share) {  // Film.with_outputs
    h.film_fx = share * r.fx;
    h.film_fy = share * r.fy;
    h.film_torque = share * r.torque_journal;
}

double film_share(const Params& a) { return a.slices > 0 ? 1.0 / a.slices : 1.0; }  // w / L, eq. (41)

// ---- the per-joint table -------------------------------------------------------------------
// One joint's state (_python_kernel.py JointKernel): per contact, its history at the start
// (prev) and at the end (cur) of the last post-processed step and its records.
// What the joint's own step control did in the last run (_python_kernel.py StepControl):
// steps it rejected, and steps it could not resolve because the solver could not shorten
// them (read by the handle after the run, which says so in an AccuracyWarning).
struct StepControl {
    bool can_shorten = true;  // the solver redoes a rejected step shorter (from the run-start callback)
    double min_step = 0.0;    // the solver's minimum step [s]
    bool rate = true;         // false: an explicit solver's error control sets the step (no rate criterion)
    std::string label;        // the joint's name, for messages (from the run-start callback)
    int group_size = 1;       // the clearance joints of the joint's system (from the run-start callback)
    double rate_scale = 1.0;  // the factor on rate_limit for this run (a convergence check's tighter run: < 1)
    double growth_cap = INF;  // the longest step free flight may grow to [s] (handle.py GROWTH_CONTACT_PERIODS)
    double jacobian_step = INF;  // the step above which the joint asks for a Jacobian per step [s] (newton.py)
    bool jacobian_on = false;    // whether it asks now
    double separation_step = INF;  // a contact that ends in a longer step is not resolved [s] (handle.py)
    double impact_mass = std::numeric_limits<double>::quiet_NaN();  // the joint's impacts' effective mass [kg] (nan: unknown)
    long separations = 0;          // contacts that ended in the run
    long long_separations = 0;     // ... in a step longer than separation_step: maybe numerical chatter
    long last_ended = 0, last_long = 0;  // what the last accepted step added (taken back if it is redone)
    long runs = 0;            // runs started since the joint was created
    long rejected = 0;        // steps rejected by the joint and redone shorter
    long unresolved = 0;      // contact steps accepted although the rate criterion asked for a shorter step
    double unresolved_time = 0.0, unresolved_step = 0.0, unresolved_advice = INF;  // the first; smallest advice
    long over_limit = 0;      // steps accepted with a penetration beyond the limit
    double over_time = 0.0, over_step = 0.0, deepest = 0.0;
    double last_time = -INF, last_step = 0.0;  // the last rejected step (to see it come back unshortened)
    double retry_start = -INF;                  // the start of the step the penetration retries are about
    int retries = 0;
};

struct JointState {
    bool in_use = true;    // false: released (its handle is gone), the slot is free for a new joint
    bool started = false;  // an accepted (initial) state exists in this run
    std::vector<Kinematics> kins;            // the last evaluation's, one per contact (storage reused)
    std::vector<History> prev, cur, initial;
    std::vector<History> next;               // scratch of the post-Newton update (storage reused)
    std::vector<std::vector<Record>> records;
    V3 omega_bearing{0.0, 0.0, 0.0};      // the bearing's angular velocity (J0), from the probe
    std::vector<FilmInput> film_inputs;  // the last evaluation's, per slice, for a lubricated joint
    FiniteCoefficients finite;                           // the finite film model's a1 ... a9 at this B/D
    V3 torque_correction{0.0, 0.0, 0.0};  // eq. (45), for the torque connector
    V3 initial_axis{0.0, 0.0, 1.0};
    double initial_axial = 0.0;
    long force_calls = 0, post_newton_calls = 0;
    std::string failure;
    double failure_time = 0.0;
    StepControl control;
    const void* group = nullptr;  // the system whose step group the joint reports to (report_growth)
    py::object run_start;  // Python callable, once per run start: (can_shorten, min_step, label, rate); None: none
};

std::vector<JointState> g_joints;
std::vector<long> g_free;  // released slots of g_joints, reused by new_joint

JointState& state(long id) {
    if (id < 0 || id >= static_cast<long>(g_joints.size()) || !g_joints[static_cast<size_t>(id)].in_use) {
        throw std::runtime_error("exuclear kernel: unknown joint id " + std::to_string(id));
    }
    return g_joints[static_cast<size_t>(id)];
}

// Record why the run cannot go on, and stop it (an exception ends Exudyn's solve; mirrors
// _python_kernel's _fail).  Only for a state that cannot go on (non-finite, a penetration
// beyond the limit that shorter steps do not remove): the message names the joint.
[[noreturn]] void fail(JointState& s, double t, const std::string& message) {
    s.failure = message;
    s.failure_time = t;
    std::string who = s.control.label.empty() ? "" : "joint " + s.control.label + ": ";
    throw std::runtime_error("exuclear: " + who + message + " at t = " + std::to_string(t) +
                             " s (joint.failure() says more)");
}

// JointKernel.start_run: a new run begins; forget the last run's step control and ask the
// handle (Python, once per run) whether the solver can shorten steps and the joint's name.
void start_run(JointState& s) {
    long runs = s.control.runs + 1;
    s.control = StepControl();
    s.control.runs = runs;
    if (!s.run_start || s.run_start.is_none()) return;
    try {  // the fields of layout.py RunStart, by name (RUN_START_FIELDS)
        py::object r = s.run_start();
        StepControl& c = s.control;
        c.can_shorten = r.attr("can_shorten").cast<bool>();
        c.min_step = r.attr("min_step").cast<double>();
        c.label = r.attr("label").cast<std::string>();
        c.rate = r.attr("rate").cast<bool>();
        c.group_size = r.attr("group_size").cast<int>();
        c.rate_scale = r.attr("rate_scale").cast<double>();
        c.growth_cap = r.attr("growth_cap").cast<double>();
        c.jacobian_step = r.attr("jacobian_step").cast<double>();
        c.separation_step = r.attr("separation_step").cast<double>();
        c.impact_mass = r.attr("impact_mass").cast<double>();
        c.jacobian_on = c.jacobian_step < INF;  // steer_newton asked for it at the first step
    } catch (py::error_already_set&) {  // never end a run for a label: keep the defaults
        PyErr_Clear();
    } catch (py::cast_error&) {
    }
}

// JointKernel.steer_jacobian: ask for a Jacobian per step while the step the joint accepts is
// longer than the run-start callback's jacobian_step (newton.py), and for the step after one in
// which a contact opened or closed or that it redoes or grows (step INF), through its
// jacobian_per_step(): a call where the ask changes, not per step.
void steer_jacobian(JointState& s, double step) {
    bool wanted = step > s.control.jacobian_step;
    if (wanted == s.control.jacobian_on) return;
    s.control.jacobian_on = wanted;
    if (!s.run_start || s.run_start.is_none()) return;
    try {
        s.run_start.attr("jacobian_per_step")(wanted);
    } catch (py::error_already_set&) {  // never end a run for a Jacobian: the setting stays as it was
        PyErr_Clear();
    }
}

// JointKernel.tell: the first step of a run that the joint could not resolve (of each kind)
// is told at once, through the run-start callback's `note()` (Python issues the
// AccuracyWarning, with its advice): a run that Exudyn then stops is not silent either.
void tell(JointState& s) {
    if (!s.run_start || s.run_start.is_none()) return;
    try {
        s.run_start.attr("note")();
    } catch (py::error_already_set&) {  // a warning filter that raises: the notes keep it
        PyErr_Clear();
    }
}

const char* const DIVERGED = "the state became non-finite (NaN or inf); the integration diverged";

struct Pose {  // the journal's centre p and axis u in J0
    V3 p, u;
};

// JointKernel._kinematics: every contact's kinematics into s.kins
Pose joint_kinematics(const Params& a, JointState& s, const V3& displacement, const V3& rotation, const V3& velocity,
                      const V3& angularVelocity) {
    int n_slices = slice_count(a);
    size_t n = contact_count(a);
    if (s.kins.size() != n) s.kins.resize(n);  // once per joint: no allocation per evaluation
    Pose q;
    V3 dv, dw, w_j;
    // the bearing's spin from the probe, where the loads use it (its probe is off otherwise)
    const V3 w_b = a.bearing_motion ? s.omega_bearing : V3{0.0, 0.0, 0.0};
    if (a.slices == 0) {  // the planar joint: the motion projected on the plane normal to the axis
        q.p = V3{displacement[0], displacement[1], 0.0};
        q.u = V3{0.0, 0.0, 1.0};
        dv = V3{velocity[0], velocity[1], 0.0};
        dw = V3{0.0, 0.0, angularVelocity[2]};
        w_j = V3{0.0, 0.0, w_b[2]};
    } else {
        q.p = displacement;
        q.u = journal_axis(rotation, a.axis_journal);                   // eq. (34)
        dv = velocity;
        dw = angularVelocity;
        w_j = w_b;
    }
    if (a.slices == 0) {  // eqs. (1)-(8): omega_i = dw_z + omega_j, the journal's own spin
        s.kins[0] = contact_kinematics(a.r_j, a.r_b, q.p[0], q.p[1], dv[0], dv[1], dw[2] + w_j[2], w_j[2]);
        if (a.film_model != FILM_NONE) {
            s.film_inputs.resize(1);
            s.film_inputs[0] = FilmInput{q.p[0], q.p[1], dv[0], dv[1], dw[2] + w_j[2], w_j[2]};
        }
    } else {
        for (int k = 0; k < n_slices; ++k) {
            s.kins[static_cast<size_t>(k)] =
                slice_kinematics(a.r_j, a.r_b, slice_centre(a.length, n_slices, k), q.p, q.u, dv, dw, w_j);
        }
        if (a.film_model != FILM_NONE) {
            s.film_inputs.resize(static_cast<size_t>(n_slices));
            for (int k = 0; k < n_slices; ++k) {
                s.film_inputs[static_cast<size_t>(k)] =
                    slice_film_input(s.kins[static_cast<size_t>(k)], q.p, q.u, dv, dw, w_j);
            }
        }
    }
    if (a.play > 0.0) {
        for (int f = 0; f < 2; ++f) {
            s.kins[static_cast<size_t>(n_slices + f)] =
                face_kinematics(a.length, a.play, a.friction_radius, FACE_SIDES[f], q.p, q.u, dv, dw, w_j);
        }
    }
    return q;
}

bool all_finite(const JointState& s) {
    for (const Kinematics& k : s.kins) {
        if (!finite(k)) return false;
    }
    return true;
}

// JointKernel.history_for: the contacts' history an evaluation at time t uses.  A time
// before the last step's start means a new run: forget everything and take this
// evaluation's state (s.kins) as the run's initial accepted state.
const std::vector<History>& history_for(JointState& s, const Params& a, const Pose& q, double t) {
    if (!s.started || t < s.prev[0].time) {
        size_t n = s.kins.size();
        s.initial_axis = q.u;
        s.initial_axial = q.p[2];
        s.records.assign(n, std::vector<Record>());
        s.failure.clear();
        start_run(s);
        s.cur.resize(n);
        for (size_t i = 0; i < n; ++i) {
            History fresh;
            fresh.time = t;
            s.cur[i] = accept(fresh, a, contact_kind(a, i), s.kins[i], t, s.records[i]);
        }
        for (size_t i = 0; i < s.film_inputs.size() && a.film_model != FILM_NONE; ++i) {
            set_film_outputs(s.cur[i], film_load(a, s.finite, s.film_inputs[i]), film_share(a));
        }
        s.prev = s.cur;
        s.initial = s.cur;
        s.started = true;
        if (!all_finite(s)) fail(s, t, DIVERGED);
    }
    return t <= s.cur[0].time ? s.prev : s.cur;
}

V6 zeros6() { return V6{0.0, 0.0, 0.0, 0.0, 0.0, 0.0}; }

// JointKernel.force_torque: [F; T] in J0, F the force on the bearing (marker 0), T minus the
// journal's moment about its marker point (Exudyn applies +F, +T to the bearing, -F, -T to
// the journal); the bearing's own moment beyond T goes to the torque connector (eq. (45)).
V6 joint_force(const Params& a, double t, const V3& displacement, const V3& rotation, const V3& velocity,
               const V3& angularVelocity) {
    JointState& s = state(a.id);
    s.force_calls++;
    Pose q = joint_kinematics(a, s, displacement, rotation, velocity, angularVelocity);
    const std::vector<History>& history = history_for(s, a, q, t);
    double loads[9] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    for (size_t i = 0; i < s.kins.size(); ++i) {
        const Kinematics& k = s.kins[i];
        if (k.delta <= 0.0) continue;
        ContactKind kind = contact_kind(a, i);
        add_loads(loads, a, kind, q.u, k, response(a, kind, history[i], k));
    }
    if (a.film_model != FILM_NONE) {  // at every eccentricity (section 10.5), on every slice
        for (size_t i = 0; i < s.film_inputs.size(); ++i) {
            FilmLoad r = film_load(a, s.finite, s.film_inputs[i]);
            if (a.slices == 0) {
                add_film_loads(loads, r);
            } else {
                add_film_slice_loads(loads, film_share(a), q.u, s.kins[i], r);
            }
        }
    }
    if (a.slices == 0) {  // the planar slice's loads hold the bearing's whole moment (eq. (26))
        s.torque_correction = V3{loads[6], loads[7], loads[8]};
    } else {
        V3 force{loads[0], loads[1], loads[2]};
        V3 pf = cross(q.p, force);                                      // eq. (45)
        s.torque_correction = V3{pf[0] + loads[6], pf[1] + loads[7], pf[2] + loads[8]};
    }
    return V6{loads[0], loads[1], loads[2], loads[3], loads[4], loads[5]};
}

void record_bearing_spin(const Params& a, const V3& angularVelocity) {  // the probe: marker 1 is the ground
    state(a.id).omega_bearing = V3{-angularVelocity[0], -angularVelocity[1], -angularVelocity[2]};
}

V6 force_torque(const MainSystem&, double t, int, V3 displacement, V3 rotation, V3 velocity, V3 angularVelocity,
                M6 parameters, M6, M3, M3, V6) {
    Params a = decode(parameters);
    switch (a.role) {
        case PROBE:  // marker 0 the bearing, marker 1 the ground: minus the bearing's spin in J0
            record_bearing_spin(a, angularVelocity);
            return zeros6();
        case TORQUE: {
            const V3& c = state(a.id).torque_correction;
            return V6{0.0, 0.0, 0.0, c[0], c[1], c[2]};
        }
        default:
            return joint_force(a, t, displacement, rotation, velocity, angularVelocity);
    }
}

// Error a post-Newton function returns to make Exudyn redo a step (above its
// discontinuous.iterationTolerance, default 1).
const double REDO_STEP_ERROR = 1e3;
// Relative slack on a step length compared with impact_step (Exudyn's steps carry round-off).
const double STEP_SLACK = 1e-9;
// Entries of the data node (exuclear/engine/layout.py DATA_COLUMNS), and a lubricated joint's
// film entries after them (FILM_DATA_COLUMNS).
const int N_DATA = 14;
const int N_FILM_DATA = 3;

// ---- the joint's own step control (_python_kernel.py JointKernel.step_control) -------------
// The fraction of a step a contact may have begun before the step's end without a redo: a
// contact that began deeper inside the step is redone so that it begins in the step's last
// ONSET_TARGET (its force then acts from about its onset on, as in the exact path): an implicit
// method charges the force at the step's end over the whole step (_python_kernel.py has the
// numbers that set these values).
const double ONSET_TAIL = 0.02;
const double ONSET_TARGET = 0.01;
// A contact that began in the step's first ONSET_FLOOR (touching at its start) is resolved
// from its start: it is not redone (that would shrink the step towards zero); the rate
// criterion resolves the rest.
const double ONSET_FLOOR = 0.05;
// ... and only in a step longer than the impact's duration (impact_duration at the joint's
// effective mass) over ONSET_IDLE_STEPS: a step that resolves the impact stays as the user chose
// it (a redo there shortens the compression's steps only, and the errors of compression and
// restitution no longer cancel; _python_kernel.py has the numbers).
const double ONSET_IDLE_STEPS = 12.0;
// Exudyn's implicit solver redoes a rejected step with at most this fraction of it
// (ReduceStepSize: the smaller of 0.75 h and the recommendation): see onset_step.
const double SOLVER_STEP_CUT = 0.75;
// The recommended step's margin below the estimate (the change of the penetration rate is
// not linear in the step: aim a little short, so that the redone step is accepted).
const double STEP_SAFETY = 0.8;
// The rate criterion shortens a step at most this much per attempt (a step still too long is
// rejected again): the change of the rate is far from linear in a long step, and a larger
// cut overshoots towards the solver's minimum step (measured on the zoo's piston engine: a
// cut from 2.1e-7 s to 1.7e-8 s, where Exudyn's Newton then failed).
const double MAX_CUT = 0.1;
// ... and never below this many times the solver's minimum step, near which Exudyn's Newton
// iteration fails (its residual falls to round-off): there the step is accepted and reported.
const double MIN_STEP_MARGIN = 10.0;
// Free flight lets the step grow (_python_kernel.py JointKernel.step_growth): after two accepted
// steps in which none of the joint's contacts touched, the next step may last until the journal
// would reach the wall at its present penetration rate and its change, up to GROWTH_LIMIT times
// the step, and only where that is GROWTH_MIN times the step or more (Exudyn's own rule doubles
// a step after 10 steps of at most 7 Newton iterations; with an impact_step, every
// recovery_steps steps).
const double GROWTH_LIMIT = 10.0;
const double GROWTH_MIN = 2.0;
// ... and only where every contact's gap exceeds GROWTH_GAP of the clearance (a journal resting
// on the wall hovers, opening by nanometres: _python_kernel.py has the measurement)
const double GROWTH_GAP = 1e-2;
// A penetration beyond the joint's limit redoes the step with this fraction of it ...
const double PENETRATION_CUT = 0.25;
// ... this many times for one step's start (the step 4^4 = 256 times shorter); a penetration
// still beyond the limit then is the contact's, not the step's: the step is accepted, the
// joint's failure() says so and the handle warns (exuclear.simulate stops the run there).
const int PENETRATION_RETRIES = 4;

std::string fmt(double x) {
    std::ostringstream o;
    o.precision(4);
    o << x;
    return o.str();
}

bool same(double x, double y) { return std::fabs(x - y) <= STEP_SLACK * std::fabs(y) + 1e-300; }

// _python_kernel.py onset_step: the step that lets a contact begun at `share` of the step h begin in
// the last ONSET_TARGET of a step: of this one, or of the second of two equal steps (SOLVER_STEP_CUT)
double onset_step(double h, double share) {
    double steps = share / (1.0 - ONSET_TARGET) <= SOLVER_STEP_CUT ? 1.0 : 2.0;
    return h * share / (steps - ONSET_TARGET);
}

// JointKernel._resolves_impact: whether a step h resolves an impact at v0 (false: mass unknown)
bool resolves_impact(const Params& a, const StepControl& c, double h, double v0) {
    double mass = c.impact_mass;
    if (!(mass > 0.0 && std::isfinite(mass))) return false;
    return h * ONSET_IDLE_STEPS <= impact_duration(a, mass, v0);
}

// Whether the step [base.time, t] resolves the joint's contacts; 0: yes (accept it), else the
// shorter step to redo it with.  A step the solver cannot shorten (its settings forbid it, its
// minimum step, or the same step came back unshortened) is accepted and counted for the
// handle's warning, as is a penetration beyond the limit that shorter steps do not remove.
//   onset: a contact with an impact velocity (|v0| > v_min) that began before the step's last
//          ONSET_TAIL, in a step longer than the impact needs (ONSET_IDLE_STEPS): redone to begin
//          at the end of a step (onset_step);
//   rate:  |delta_dot_end - delta_dot_start| > KAPPA max(|v0|, v_min) in a contact (or one that
//          began or ended in the step): several steps per velocity reversal, with neither the
//          mass nor the law in the criterion.  Settled contacts (|v0| at the v_min floor) are
//          limited too (exempting them left 5x simulate's penetration on the zoo's piston
//          engine, and more steps; _python_kernel.py step_control has the numbers).
double step_control(const Params& a, JointState& s, const std::vector<History>& base, double t) {
    StepControl& c = s.control;
    double h = t - base[0].time;
    if (!(h > 0.0)) return 0.0;
    bool repeated = same(t, c.last_time) && same(h, c.last_step);  // the solver did not shorten it
    bool shortens = c.can_shorten && !repeated && h > c.min_step * (1.0 + STEP_SLACK);
    double deepest = -INF;
    for (const Kinematics& k : s.kins) deepest = k.delta > deepest ? k.delta : deepest;
    if (deepest > a.max_penetration) {
        if (!same(base[0].time, c.retry_start)) {
            c.retry_start = base[0].time;
            c.retries = 0;
        }
        if (shortens && c.retries < PENETRATION_RETRIES) {
            c.retries++;
            c.rejected++;
            c.last_time = t;
            c.last_step = h;
            double h_new = h * PENETRATION_CUT;
            return h_new > c.min_step ? h_new : c.min_step * (1.0 + STEP_SLACK);
        }
        if (c.over_limit == 0) {  // accepted: the run goes on, the handle says so (a simulate run stops)
            c.over_time = t;
            c.over_step = h;
            s.failure = "penetration " + fmt(deepest) + " m exceeds the limit " + fmt(a.max_penetration) + " m";
            s.failure_time = t;
        }
        c.over_limit++;
        c.deepest = deepest > c.deepest ? deepest : c.deepest;
        if (c.over_limit == 1) tell(s);
    }
    // an explicit impact_step overrides the rate criterion (the caller resolves contacts so)
    double kappa = c.rate && !(a.impact_step > 0.0) ? a.rate_limit * c.rate_scale : 0.0;
    if (!(kappa > 0.0)) return 0.0;
    double h_rec = INF;
    double h_need = INF;  // the rate criterion's estimate without the cap: the advice of a note
    bool rate_exceeded = false;
    for (size_t i = 0; i < s.kins.size(); ++i) {
        const Kinematics& k = s.kins[i];
        const History& b = base[i];
        if (k.delta <= 0.0 && !b.in_contact) continue;  // free flight: nothing limits the step
        bool onset = !b.in_contact;
        double v0 = onset ? onset_velocity(b, k.delta, k.delta_dot) : b.v0;
        bool impact = std::fabs(v0) > a.v_min;
        if (impact && onset && b.delta != -INF && !resolves_impact(a, c, h, v0)) {
            double share = b.delta / (b.delta - k.delta);  // the onset's fraction of the step
            if (1.0 - share > ONSET_TAIL && share > ONSET_FLOOR) {
                double h_on = onset_step(h, share);
                h_rec = h_on < h_rec ? h_on : h_rec;
            }
        }
        double change = std::fabs(k.delta_dot - b.delta_dot);
        double allowed = kappa * (impact ? std::fabs(v0) : a.v_min);
        if (change > allowed) {
            double h_rate = STEP_SAFETY * h * allowed / change;
            if (impact) h_need = h_rate < h_need ? h_rate : h_need;
            h_rate = h_rate > MAX_CUT * h ? h_rate : MAX_CUT * h;
            h_rec = h_rate < h_rec ? h_rate : h_rec;
            // reported only for an impact: a settled contact's rate at a fixed step is the load's
            // (measured: the resting pendulum of tests/test_robust.py, right at its fixed step)
            rate_exceeded = rate_exceeded || impact;
        }
    }
    if (h_rec == INF) return 0.0;
    double floor = MIN_STEP_MARGIN * c.min_step;
    if (h_rec < floor) h_rec = floor;
    if (shortens && h > floor * (1.0 + STEP_SLACK)) {
        c.rejected++;
        c.last_time = t;
        c.last_step = h;
        return h_rec > c.min_step ? h_rec : c.min_step * (1.0 + STEP_SLACK);
    }
    if (rate_exceeded) {  // accepted unresolved: say so after the run
        if (c.unresolved == 0) {
            c.unresolved_time = t;
            c.unresolved_step = h;
        }
        c.unresolved++;
        h_need = h_need > floor ? h_need : floor;
        c.unresolved_advice = h_need < c.unresolved_advice ? h_need : c.unresolved_advice;
        if (c.unresolved == 1) tell(s);  // with its advice
    }
    return 0.0;
}

// _python_kernel.py time_to_wall: the smallest positive root of delta + delta_dot tau + delta_ddot tau^2 / 2
double time_to_wall(double delta, double delta_dot, double delta_ddot) {
    if (delta_ddot == 0.0) return delta_dot > 0.0 ? -delta / delta_dot : INF;
    double disc = delta_dot * delta_dot - 2.0 * delta_ddot * delta;
    if (disc < 0.0) return INF;  // moving away and slowing down towards the wall: it turns before it
    double q = delta_dot + std::copysign(std::sqrt(disc), delta_dot != 0.0 ? delta_dot : 1.0);
    double r1 = q != 0.0 ? -2.0 * delta / q : INF, r2 = -q / delta_ddot;
    double best = INF;
    if (r1 > 0.0) best = r1;
    if (r2 > 0.0 && r2 < best) best = r2;
    return best;
}

// JointKernel.step_growth: the next step the joint's free flight allows after the accepted step
// from base to end, the step before it starting at `before` (0: it asks for none).
double step_growth(const Params& a, const std::vector<History>& before, const std::vector<History>& base,
                   const std::vector<History>& end, double t) {
    const StepControl& c = state(a.id).control;
    double h = t - base[0].time;
    if (!(c.can_shorten && c.rate && a.rate_limit > 0.0 && a.film_model == FILM_NONE && h > 0.0)) {
        return 0.0;
    }
    double allow = GROWTH_LIMIT * h < c.growth_cap ? GROWTH_LIMIT * h : c.growth_cap;
    const double gap = GROWTH_GAP * (a.r_b - a.r_j);
    for (size_t i = 0; i < end.size(); ++i) {
        const History& e = end[i];
        if (before[i].in_contact || base[i].in_contact || e.in_contact || -e.delta < gap) return 0.0;
        double to_wall = time_to_wall(e.delta, e.delta_dot, (e.delta_dot - base[i].delta_dot) / h);
        allow = to_wall < allow ? to_wall : allow;
    }
    return allow >= GROWTH_MIN * h ? allow : 0.0;
}

// The step group of a system (JointKernel.report_growth): the time of the step its joints report
// on, the smallest allowance reported for it, which joints did, and how many joints belong to it.
struct StepGroup {
    double t = -INF;
    double allow = INF;
    std::vector<long> reported;
    long members = 0;
};
std::unordered_map<const void*, StepGroup> g_groups;  // by the address of the joints' MainSystem

void leave_group(JointState& s) {
    if (s.group == nullptr) return;
    auto it = g_groups.find(s.group);
    if (it != g_groups.end() && --it->second.members <= 0) g_groups.erase(it);
    s.group = nullptr;
}

// JointKernel.report_growth: the last of a system's joints to report on a step lets the solver's
// next step grow to the smallest allowance, through the run-start callback's grow().
void report_growth(JointState& s, long id, const void* system, double t, double allow, double h) {
    if (!s.run_start || s.run_start.is_none()) return;
    if (s.group != system) {
        leave_group(s);
        s.group = system;
        g_groups[system].members++;
    }
    StepGroup& g = g_groups[system];
    if (g.t != t) {
        g.t = t;
        g.allow = INF;
        g.reported.clear();
    }
    g.allow = allow < g.allow ? allow : g.allow;
    if (std::find(g.reported.begin(), g.reported.end(), id) == g.reported.end()) g.reported.push_back(id);
    if (static_cast<int>(g.reported.size()) == s.control.group_size && g.allow >= GROWTH_MIN * h) {
        steer_jacobian(s, INF);  // the grown step: a Jacobian for it
        try {
            s.run_start.attr("grow")(g.allow);
        } catch (py::error_already_set&) {  // never end a run for a longer step: Exudyn's own rule
            PyErr_Clear();
        }
    }
}

// Appends a history's data-node entries (layout.DATA_COLUMNS) from entry `first` on.
void write_data(const History& h, StdVector& out, int first = 0) {
    double values[N_DATA] = {h.time, h.delta == -INF ? 0.0 : h.delta, h.delta_dot, h.ex, h.ey, h.f_n, h.f_t, h.v_t,
                             h.v0, h.in_contact ? 1.0 : 0.0, static_cast<double>(h.onsets), h.onset_time,
                             h.peak_force, h.max_penetration};
    for (int i = first; i < N_DATA; ++i) out.push_back(values[i]);
}


// JointKernel.count_separations: the contacts that ended in an accepted step of length h, and
// those of them in a step longer than separation_step; a step accepted again from the same
// start (redone after another item rejected it) replaces its first count.
void count_separations(StepControl& c, bool advance, long ended, double h) {
    if (!advance) {
        c.separations -= c.last_ended;
        c.long_separations -= c.last_long;
    }
    c.last_ended = ended;
    c.last_long = h > c.separation_step * (1.0 + STEP_SLACK) ? ended : 0;
    c.separations += c.last_ended;
    c.long_separations += c.last_long;
}

// JointKernel.post_newton: the contacts' history update, once per accepted step.
// Returns [error, recommended step, data...].
// The reply of a post-Newton function, [error = 0, recommended step = -1], with room for the
// data node's n entries after it: one allocation per call (Exudyn counts a run's allocations
// and warns where they come every step).
StdVector reply(size_t n) {
    StdVector out;
    out.reserve(2 + n);
    out.push_back(0.0);
    out.push_back(-1.0);
    return out;
}

StdVector joint_post_newton(const Params& a, const void* system, double t, const StdVector& data,
                            const V3& displacement, const V3& rotation, const V3& velocity,
                            const V3& angularVelocity) {
    StdVector out = reply(data.size());
    JointState& s = state(a.id);
    s.post_newton_calls++;
    Pose q = joint_kinematics(a, s, displacement, rotation, velocity, angularVelocity);
    history_for(s, a, q, t);  // starts a run if needed
    bool advance = t > s.cur[0].time;
    const std::vector<History>& base = advance ? s.cur : s.prev;  // a repeated step starts again from its start
    if (!all_finite(s)) fail(s, t, DIVERGED);
    size_t n = s.kins.size();
    if (a.impact_step > 0.0 && t - base[0].time > a.impact_step * (1.0 + STEP_SLACK)) {
        bool run_start = base[0].time == s.initial[0].time;  // the step from the run's initial state
        for (size_t i = 0; i < n; ++i) {
            // a contact begins in a long step, or the run begins in an impact: redo it with impact_step
            if ((!base[i].in_contact && s.kins[i].delta > 0.0) ||
                (run_start && base[i].in_contact && std::fabs(base[i].v0) > a.v_min)) {
                steer_jacobian(s, INF);  // a step of another length: a Jacobian for it
                out[0] = REDO_STEP_ERROR;
                out[1] = a.impact_step;
                out.insert(out.end(), data.begin(), data.end());
                return out;
            }
        }
    }
    double redo = step_control(a, s, base, t);
    if (redo > 0.0) {
        steer_jacobian(s, INF);
        out[0] = REDO_STEP_ERROR;
        out[1] = redo;
        out.insert(out.end(), data.begin(), data.end());
        return out;
    }
    s.next.resize(n);
    for (size_t i = 0; i < n; ++i) {
        s.records[i].resize(static_cast<size_t>(base[i].closed));
        s.next[i] = accept(base[i], a, contact_kind(a, i), s.kins[i], t, s.records[i]);
        if (!std::isfinite(s.next[i].f_n)) fail(s, t, "the contact force became non-finite (NaN or inf)");
    }
    for (size_t i = 0; i < s.film_inputs.size() && a.film_model != FILM_NONE; ++i) {
        set_film_outputs(s.next[i], film_load(a, s.finite, s.film_inputs[i]), film_share(a));
    }
    // the step before this one: free flight must have lasted both (a repeated step: unknown)
    double allow = advance ? step_growth(a, s.prev, base, s.next, t) : 0.0;
    double h = t - base[0].time;
    bool switched = false;  // a contact opened or closed in this step: its stiffness came or went
    long ended = 0;         // contacts that ended in this step
    for (size_t i = 0; i < n; ++i) {
        switched = switched || base[i].in_contact != s.next[i].in_contact;
        if (base[i].in_contact && !s.next[i].in_contact) ended++;
    }
    count_separations(s.control, advance, ended, h);
    if (advance) s.prev.swap(s.cur);  // prev = the old cur; base is not read after this
    s.cur.swap(s.next);
    steer_jacobian(s, switched ? INF : h);
    report_growth(s, a.id, system, t, allow, h);
    if (a.slices == 0) {  // the planar data node: layout.DATA_COLUMNS (and FILM_DATA_COLUMNS)
        write_data(s.cur[0], out);
        if (a.film_model != FILM_NONE) {
            out.push_back(s.cur[0].film_fx);
            out.push_back(s.cur[0].film_fy);
            out.push_back(s.cur[0].film_torque);
        }
        return out;
    }
    // layout.spatial_data_columns, as many entries as the data node has (reserved by reply)
    out.push_back(t);
    out.push_back(q.u[0]);
    out.push_back(q.u[1]);
    out.push_back(q.p[2]);
    for (const History& h : s.cur) write_data(h, out, 1);  // each contact's entries without its time
    if (a.film_model != FILM_NONE) {  // then each slice's film entries (layout.FILM_DATA_COLUMNS)
        for (size_t i = 0; i < s.film_inputs.size(); ++i) {
            out.push_back(s.cur[i].film_fx);
            out.push_back(s.cur[i].film_fy);
            out.push_back(s.cur[i].film_torque);
        }
    }
    return out;
}

StdVector post_newton(const MainSystem& mbs, double t, int, StdVector data, V3 displacement, V3 rotation,
                      V3 velocity, V3 angularVelocity, M6 parameters, M6, M3, M3, V6) {
    Params a = decode(parameters);
    if (a.role == PROBE) {
        record_bearing_spin(a, angularVelocity);
        StdVector out = reply(data.size());
        out.insert(out.end(), data.begin(), data.end());
        return out;
    }
    return joint_post_newton(a, &mbs, t, data, displacement, rotation, velocity, angularVelocity);
}

// ---- dispatch counter for the self-test -----------------------------------------------------
long g_dispatch_calls = 0;
struct DispatchCounter {  // constructed only when a call comes through pybind11's Python dispatcher
    DispatchCounter() { ++g_dispatch_calls; }
};

py::dict history_dict(const History& h) {
    py::dict d;
    d["time"] = h.time;
    d["delta"] = h.delta;
    d["delta_dot"] = h.delta_dot;
    d["in_contact"] = h.in_contact;
    d["v0"] = h.v0;
    d["onsets"] = h.onsets;
    d["closed"] = h.closed;
    d["onset_time"] = h.onset_time;
    d["peak_force"] = h.peak_force;
    d["max_penetration"] = h.max_penetration;
    d["normal_force"] = h.f_n;
    d["tangential_force"] = h.f_t;
    d["slip_velocity"] = h.v_t;
    d["ecc_x"] = h.ex;
    d["ecc_y"] = h.ey;
    d["film_fx"] = h.film_fx;
    d["film_fy"] = h.film_fy;
    d["film_torque"] = h.film_torque;
    return d;
}

py::list history_list(const std::vector<History>& hs) {
    py::list l;
    for (const History& h : hs) l.append(history_dict(h));
    return l;
}

}  // namespace

PYBIND11_MODULE(_ckernel, m) {
    m.doc() = "Compiled kernel of the exuclear clearance joint (see exuclear/engine/kernel.py)";
    m.def("force_torque", &force_torque, py::call_guard<DispatchCounter>(),
          "springForceTorqueUserFunction of the clearance-joint connectors");
    m.def("post_newton", &post_newton, py::call_guard<DispatchCounter>(),
          "postNewtonStepUserFunction of the clearance-joint connectors");
    m.def("new_joint", []() {
        if (!g_free.empty()) {  // reuse a released slot
            long id = g_free.back();
            g_free.pop_back();
            g_joints[static_cast<size_t>(id)] = JointState();
            return id;
        }
        g_joints.emplace_back();
        return static_cast<long>(g_joints.size() - 1);
    }, "a new joint's id in the kernel's table");
    m.def("release", [](long id) {
        leave_group(state(id));
        state(id) = JointState();
        g_joints[static_cast<size_t>(id)].in_use = false;
        g_free.push_back(id);
    }, "free a joint's state (its handle is gone); new_joint reuses the slot");
    m.def("joints_in_use", []() { return static_cast<long>(g_joints.size() - g_free.size()); });
    m.def("reset", [](long id) {  // forget the history; keep the run-start callback and the run count
        JointState& s = state(id);
        py::object run_start = s.run_start;
        long runs = s.control.runs;
        leave_group(s);
        s = JointState();
        s.run_start = run_start;
        s.control.runs = runs;
    });
    m.def("set_run_start", [](long id, py::object callback) { state(id).run_start = callback; },
          "a callable called once per run start: (can_shorten, min_step, label, rate); hold no strong "
          "reference to the joint's handle in it");
    m.def("step_control", [](long id) {  // what the joint's own step control did in the last run
        const StepControl& c = state(id).control;
        py::dict d;
        d["runs"] = c.runs;
        d["can_shorten"] = c.can_shorten;
        d["min_step"] = c.min_step;
        d["rate"] = c.rate;
        d["label"] = c.label;
        d["group_size"] = c.group_size;
        d["rate_scale"] = c.rate_scale;
        d["growth_cap"] = c.growth_cap;
        d["jacobian_step"] = c.jacobian_step;
        d["jacobian_on"] = c.jacobian_on;
        d["separation_step"] = c.separation_step;
        d["impact_mass"] = c.impact_mass;
        d["separations"] = c.separations;
        d["long_separations"] = c.long_separations;
        d["rejected"] = c.rejected;
        d["unresolved"] = c.unresolved;
        d["unresolved_time"] = c.unresolved_time;
        d["unresolved_step"] = c.unresolved_step;
        d["unresolved_advice"] = c.unresolved_advice;
        d["over_limit"] = c.over_limit;
        d["over_time"] = c.over_time;
        d["over_step"] = c.over_step;
        d["deepest"] = c.deepest;
        return d;
    });
    m.def("dispatch_calls", []() { return g_dispatch_calls; });
    m.def("impact_duration", [](M6 parameters, double mass, double speed) {
        return impact_duration(decode(parameters), mass, speed);
    }, "timescales.impact_duration of the joint whose parameter matrix is given (a test hook)");
    m.def("time_force", [](M6 parameters, V3 displacement, V3 velocity, V3 angularVelocity, double t, long n) {
        // seconds per force_torque evaluation, n evaluations at one state (validation/film_cost.py)
        V3 rotation{0.0, 0.0, 0.0};
        volatile double sink = 0.0;  // keeps the evaluations from being optimised away
        auto start = std::chrono::steady_clock::now();
        for (long i = 0; i < n; ++i) {  // what force_torque does for the joint's connector: decode, evaluate
            Params a = decode(parameters);
            V6 f = joint_force(a, t, displacement, rotation, velocity, angularVelocity);
            sink = sink + f[0];
        }
        std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
        return elapsed.count() / static_cast<double>(n);
    }, "seconds per evaluation of the joint's force function (a micro benchmark)");
    m.def("calls", [](long id) {
        JointState& s = state(id);
        return py::make_tuple(s.force_calls, s.post_newton_calls);
    });
    m.def("history", [](long id) {  // per contact: slices (one for the planar joint), then end faces
        JointState& s = state(id);
        py::dict d;
        d["started"] = s.started;
        d["current"] = history_list(s.cur);
        d["previous"] = history_list(s.prev);
        d["initial"] = history_list(s.initial);
        return d;
    });
    m.def("records", [](long id) {  // per contact
        JointState& s = state(id);
        py::list out;
        for (const std::vector<Record>& rs : s.records) {
            py::list l;
            for (const Record& r : rs) {
                l.append(py::make_tuple(r.onset_time, r.onset_velocity, r.peak_force, r.duration, r.max_penetration));
            }
            out.append(l);
        }
        return out;
    });
    m.def("initial_axis", [](long id) {
        JointState& s = state(id);
        return py::make_tuple(py::make_tuple(s.initial_axis[0], s.initial_axis[1], s.initial_axis[2]),
                              s.initial_axial);
    });
    m.def("failure", [](long id) {
        JointState& s = state(id);
        return py::make_tuple(s.failure, s.failure_time);
    });
    m.def("failed", [](long id) { return !state(id).failure.empty(); });  // per step, cheap: no string
    py::list layout;
    for (const FieldPosition& f : LAYOUT) layout.append(py::make_tuple(f.name, f.row, f.column, f.size));
    m.attr("LAYOUT") = layout;
    m.attr("N_DATA") = N_DATA;
    m.attr("N_FILM_DATA") = N_FILM_DATA;
    m.attr("STIFFNESS_CODES") = STIFFNESS_CODES;
    // the run-start record's fields start_run reads (layout.py RunStart), and the step
    // control's constants (_python_kernel.py), which tests keep equal to Python's
    py::list run_start_fields;
    for (const char* name : {"can_shorten", "min_step", "label", "rate", "group_size", "rate_scale", "growth_cap",
                             "jacobian_step", "separation_step", "impact_mass"}) {
        run_start_fields.append(name);
    }
    m.attr("RUN_START_FIELDS") = run_start_fields;
    py::dict constants;
    constants["REDO_STEP_ERROR"] = REDO_STEP_ERROR;
    constants["STEP_SLACK"] = STEP_SLACK;
    constants["ONSET_TAIL"] = ONSET_TAIL;
    constants["ONSET_TARGET"] = ONSET_TARGET;
    constants["ONSET_FLOOR"] = ONSET_FLOOR;
    constants["ONSET_IDLE_STEPS"] = ONSET_IDLE_STEPS;
    constants["SOLVER_STEP_CUT"] = SOLVER_STEP_CUT;
    constants["STEP_SAFETY"] = STEP_SAFETY;
    constants["MAX_CUT"] = MAX_CUT;
    constants["MIN_STEP_MARGIN"] = MIN_STEP_MARGIN;
    constants["GROWTH_LIMIT"] = GROWTH_LIMIT;
    constants["GROWTH_MIN"] = GROWTH_MIN;
    constants["GROWTH_GAP"] = GROWTH_GAP;
    constants["PENETRATION_CUT"] = PENETRATION_CUT;
    constants["PENETRATION_RETRIES"] = PENETRATION_RETRIES;
    m.attr("STEP_CONSTANTS") = constants;
}
