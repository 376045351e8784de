// Compiled kernel of the exuclear clearance joint.
//
// The same formulas as the Python statement of the physics, in the same order and with
// the same names, so that the two can be read side by side and agree to round-off:
//   contact kinematics  exuclear/geometry.py   (docs/physics.md eqs. (1)-(8))
//   normal force        exuclear/contact.py    (eqs. (9)-(17))
//   friction            exuclear/friction.py   (eqs. (20)-(23))
//   loads               exuclear/geometry.py   (eqs. (24)-(26))
//   contact history     exuclear/history.py    (onset velocity, records)
//   step bookkeeping    exuclear/engine/_python_kernel.py (which history an evaluation uses)
//   spatial joint       exuclear/spatial.py and SpatialJointKernel in _python_kernel.py
//                       (eqs. (33)-(45)): the same names, the drivers spatial_*; its axial clearance
//                       (eqs. (48)-(54)): functions face_*
//
// Exudyn calls these functions through raw function pointers, without Python, when they
// are bound by pybind11, capture nothing and have exactly Exudyn's signature
// (see exuclear/engine/kernel.py, which checks that at import).
// Parameters reach the functions through the connector's `stiffness` matrix (layout in
// exuclear/engine/layout.py); the per-joint dynamic state lives in a table indexed by the
// joint id stored there.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
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

// ---- parameters (layout: exuclear/engine/layout.py) -------------------------------------
enum Role { MAIN = 0, PROBE = 1, TORQUE = 2 };
enum FrictionCode { FRICTION_NONE = 0, FRICTION_COULOMB = 1, FRICTION_MODIFIED_COULOMB = 2 };

struct Params {
    long id;
    int role;
    double r_j, r_b, max_penetration, impact_step;
    int stiffness_code;
    double exponent, damping_factor, v_min, clearance;
    double kp[6];
    int friction_code;
    double fp[4];
    int slices;  // 0: the planar joint; N > 0: the spatial joint of N slices
    double length;
    V3 axis_journal;
    // the spatial joint's axial clearance (section 9.6): total play (0: none), shoulder,
    // friction radius R_e, face stiffness K_f
    double play, shoulder_radius, friction_radius, face_stiffness;
};

Params decode(const M6& p) {
    Params a;
    a.id = static_cast<long>(p[0][0]);
    a.role = static_cast<int>(p[0][1]);
    a.r_j = p[0][2];
    a.r_b = p[0][3];
    a.max_penetration = p[0][4];
    a.impact_step = p[0][5];
    a.stiffness_code = static_cast<int>(p[1][0]);
    a.exponent = p[1][2];
    a.damping_factor = p[1][3];
    a.v_min = p[1][4];
    a.clearance = p[1][5];
    for (int i = 0; i < 6; ++i) a.kp[i] = p[2][i];
    a.friction_code = static_cast<int>(p[3][0]);
    for (int i = 0; i < 4; ++i) a.fp[i] = p[3][i + 1];
    a.slices = static_cast<int>(p[5][0]);
    a.length = p[5][1];
    a.axis_journal = V3{p[5][2], p[5][3], p[5][4]};
    a.play = p[4][1];
    a.shoulder_radius = p[4][2];
    a.friction_radius = p[4][3];
    a.face_stiffness = p[4][4];
    return a;
}

// ---- physics: geometry.py ------------------------------------------------------------------
struct Kinematics {
    double ex, ey, ecc, nx, ny, delta, delta_dot, v_t;
};

// contact_kinematics + kinematics_along (eqs. (1)-(8)), in the joint frame J0 of the bearing
Kinematics contact_kinematics(const Params& a, double ex, double ey, double dvx, double dvy, double omega_i,
                              double omega_j) {
    Kinematics k;
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
    k.v_t = dvx * k.ny - dvy * k.nx - omega_i * a.r_j + omega_j * a.r_b;               // eq. (8)
    k.delta = k.ecc - (a.r_b - a.r_j);                                                 // eq. (4)
    return k;
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

double normal_force(const Params& a, double delta, double delta_dot, double v0) {  // eq. (9)
    if (delta <= 0.0) return 0.0;
    double v0_eff = v0 > a.v_min ? v0 : a.v_min;
    double f = elastic_force(a, delta) * (1.0 + a.damping_factor * delta_dot / v0_eff);
    return f < 0.0 ? 0.0 : f;  // no adhesion; a NaN stays NaN, to be caught
}

// spatial.py face_normal_force, eq. (53): eq. (9) with F_e = K_f delta, the law's D and v_min
double face_normal_force(double k_face, double damping_factor, double v_min, double delta, double delta_dot,
                         double v0) {
    if (delta <= 0.0) return 0.0;
    double v0_eff = v0 > v_min ? v0 : v_min;
    double f = k_face * delta * (1.0 + damping_factor * delta_dot / v0_eff);
    return f < 0.0 ? 0.0 : f;  // a NaN stays NaN, to be caught
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

// ContactState.accept (exuclear/history.py): the history after an accepted state (kinematics k, time t);
// a contact that ends appends its record.  law_share: a spatial slice's share w / L of the
// law (eq. (41)); 1 for the planar joint (x * 1.0 == x, so the planar joint is unchanged).
// face: an end face of the axial clearance, whose force is eq. (53) (_FaceJoint).
History accept(const History& h, const Params& a, const Kinematics& k, double time, std::vector<Record>& records,
               double law_share = 1.0, bool face = false) {
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
    n.v_t = k.v_t;
    n.f_n = !n.in_contact ? 0.0
            : face      ? face_normal_force(a.face_stiffness, a.damping_factor, a.v_min, delta, delta_dot, n.v0)
                        : law_share * normal_force(a, delta, delta_dot, n.v0);
    n.f_t = n.in_contact && a.friction_code != FRICTION_NONE ? friction_coefficient(a, k.v_t) * n.f_n : 0.0;
    if (n.in_contact) {
        n.peak_force = n.f_n > n.peak_force ? n.f_n : n.peak_force;
        n.max_penetration = delta > n.max_penetration ? delta : n.max_penetration;
    }
    return n;
}

// ---- the per-joint table -------------------------------------------------------------------
struct JointState {
    bool started = false;  // an accepted (initial) state exists in this run
    History prev, cur;     // history at the start and at the end of the last post-processed step
    History initial;       // the run's initial accepted state
    std::vector<Record> records;
    double omega_bearing = 0.0;    // bearing's angular velocity about the axis, from the probe
    double torque_correction = 0.0;  // m_i + m_j, for the torque connector
    // the spatial joint (one History per slice, then per end face with an axial clearance)
    std::vector<History> sprev, scur, sinitial;
    std::vector<std::vector<Record>> srecords;
    V3 omega_bearing3{0.0, 0.0, 0.0};      // the bearing's angular velocity (J0), from the probe
    V3 torque_correction3{0.0, 0.0, 0.0};  // eq. (45), for the torque connector
    V3 initial_axis{0.0, 0.0, 1.0};
    double initial_axial = 0.0;
    long force_calls = 0, post_newton_calls = 0;
    std::string failure;
    double failure_time = 0.0;
};

std::vector<JointState> g_joints;

JointState& state(long id) {
    if (id < 0 || id >= static_cast<long>(g_joints.size())) {
        throw std::runtime_error("exuclear kernel: unknown joint id " + std::to_string(id));
    }
    return g_joints[static_cast<size_t>(id)];
}

// Record why the run cannot go on, and stop it (an exception ends Exudyn's solve; mirrors
// _python_kernel's _fail).
[[noreturn]] void fail(JointState& s, double t, const std::string& message) {
    s.failure = message;
    s.failure_time = t;
    throw std::runtime_error("exuclear: " + message);
}

// Which history an evaluation at time t uses (mirrors _python_kernel.PythonJointKernel.history_for).
// A time before the last step's start means a new run: forget everything and take this
// evaluation's state as the run's initial accepted state.
const History& history_for(JointState& s, const Params& a, const Kinematics& k, double t) {
    if (!s.started || t < s.prev.time) {
        s.records.clear();
        s.failure.clear();
        History fresh;
        fresh.time = t;
        s.cur = accept(fresh, a, k, t, s.records);
        s.prev = s.cur;
        s.initial = s.cur;
        s.started = true;
        if (!(std::isfinite(k.ex) && std::isfinite(k.ey) && std::isfinite(k.delta_dot) && std::isfinite(k.v_t))) {
            fail(s, t, "the state became non-finite (NaN or inf); the integration diverged");
        }
    }
    return t <= s.cur.time ? s.prev : s.cur;
}

V6 zeros6() { return V6{0.0, 0.0, 0.0, 0.0, 0.0, 0.0}; }

// ---- the connector's force (eqs. (24)-(26)) ---------------------------------------------------------
// Returns [F; T] in J0 coordinates: the bearing (marker 0) receives +F, +T, the journal
// (marker 1) -F, -T.  F = -F_i and T = -M_i; the bearing's own moment M_j differs from
// -M_i by (R_J - R_B) F_T, which the torque connector adds.
V6 main_force(const Params& a, double t, const V3& displacement, const V3& velocity, const V3& angularVelocity) {
    JointState& s = state(a.id);
    s.force_calls++;
    double omega_j = s.omega_bearing;
    double omega_i = angularVelocity[2] + omega_j;
    Kinematics k = contact_kinematics(a, displacement[0], displacement[1], velocity[0], velocity[1], omega_i, omega_j);
    const History& h = history_for(s, a, k, t);
    if (k.delta <= 0.0) {
        s.torque_correction = 0.0;
        return zeros6();
    }
    double v0 = onset_velocity(h, k.delta, k.delta_dot);
    double f_n = normal_force(a, k.delta, k.delta_dot, v0);
    double f_t = a.friction_code != FRICTION_NONE ? friction_coefficient(a, k.v_t) * f_n : 0.0;
    // joint_loads
    double fx = -f_n * k.nx - f_t * k.ny;
    double fy = -f_n * k.ny + f_t * k.nx;
    double m_i = a.r_j * f_t;
    double m_j = -a.r_b * f_t;
    s.torque_correction = m_j + m_i;
    return V6{-fx, -fy, 0.0, 0.0, 0.0, -m_i};
}

// ---- the spatial joint: spatial.py (docs/physics.md section 9, eqs. (33)-(45)) --------------
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

struct SliceKinematics {
    double s, ex, ey, ecc, nx, ny, a, delta, delta_dot, v_t, v_a, speed;
};

SliceKinematics slice_kinematics(double r_j, double r_b, double z, const V3& p, const V3& u, const V3& dv,
                                 const V3& dw, const V3& w_j) {
    SliceKinematics k;
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

void slice_friction(double mu, double f_n, const SliceKinematics& k, double& f_t, double& f_a) {  // eq. (42)
    if (!(k.speed > 0.0)) {
        f_t = 0.0;
        f_a = 0.0;
        return;
    }
    double g = mu * f_n;
    f_t = g * (k.v_t / k.speed);
    f_a = g * (k.v_a / k.speed);
}

// loads = [force (3), torque (3), correction (3)], eqs. (43)-(45)
void add_slice_loads(double* loads, double r_j, const V3& u, const SliceKinematics& k, double f_n, double f_t,
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

// ---- axial clearance: spatial.py face_* (docs/physics.md section 9.6, eqs. (48)-(54)) ----------
const int FACE_SIDES[2] = {-1, 1};  // face 0 at z = -L/2, face 1 at z = +L/2

struct FaceKinematics {
    int side;
    double s, ex, ey, delta, delta_dot, v_t;
};

FaceKinematics face_kinematics(double length, double play, double r_e, int side, const V3& p, const V3& u,
                               const V3& dv, const V3& dw, const V3& w_j) {
    FaceKinematics k;
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

// loads = [force (3), torque (3), correction (3)]; eq. (54)
void add_face_loads(double* loads, double r_e, const V3& u, const FaceKinematics& k, double f_n, double f_t) {
    V3 total{0.0, 0.0, -k.side * f_n};                                  // on the bearing, at c_f
    V3 su{k.s * u[0], k.s * u[1], k.s * u[2]};
    V3 arm = cross(su, total);
    V3 couple{r_e * f_t * u[0], r_e * f_t * u[1], r_e * f_t * u[2]};
    for (int i = 0; i < 3; ++i) {
        loads[i] += total[i];                                           // eq. (54)
        loads[3 + i] += arm[i] + couple[i];                             // eq. (54); the correction is p x F
    }
}

Kinematics face_accepted(const FaceKinematics& k) {  // _accepted: an end face records its signed slip
    Kinematics a;
    a.ex = k.ex;
    a.ey = k.ey;
    a.ecc = 0.0;
    a.nx = 1.0;
    a.ny = 0.0;
    a.delta = k.delta;
    a.delta_dot = k.delta_dot;
    a.v_t = k.v_t;
    return a;
}

bool face_finite(const FaceKinematics& k) {
    return std::isfinite(k.ex) && std::isfinite(k.ey) && std::isfinite(k.delta_dot) && std::isfinite(k.v_t);
}

Kinematics slice_accepted(const SliceKinematics& k) {  // _accepted: what accept reads; v_t the slip speed
    Kinematics a;
    a.ex = k.ex;
    a.ey = k.ey;
    a.ecc = k.ecc;
    a.nx = k.nx;
    a.ny = k.ny;
    a.delta = k.delta;
    a.delta_dot = k.delta_dot;
    a.v_t = k.speed;
    return a;
}

bool slice_finite(const SliceKinematics& k) {
    return std::isfinite(k.ex) && std::isfinite(k.ey) && std::isfinite(k.delta_dot) && std::isfinite(k.v_t);
}

struct SpatialInput {
    V3 p, u;
    std::vector<SliceKinematics> kins;
    std::vector<FaceKinematics> faces;  // empty without an axial clearance
};

SpatialInput spatial_kinematics(const Params& a, const JointState& s, const V3& displacement, const V3& rotation,
                                const V3& velocity, const V3& angularVelocity) {
    SpatialInput in;
    in.p = displacement;
    in.u = journal_axis(rotation, a.axis_journal);                     // eq. (34)
    in.kins.reserve(static_cast<size_t>(a.slices));
    for (int k = 0; k < a.slices; ++k) {  // no per-evaluation allocation of the centres
        in.kins.push_back(slice_kinematics(a.r_j, a.r_b, slice_centre(a.length, a.slices, k), in.p, in.u, velocity,
                                           angularVelocity, s.omega_bearing3));
    }
    if (a.play > 0.0) {
        for (int side : FACE_SIDES) {
            in.faces.push_back(face_kinematics(a.length, a.play, a.friction_radius, side, in.p, in.u, velocity,
                                               angularVelocity, s.omega_bearing3));
        }
    }
    return in;
}

// SpatialJointKernel.history_for: the slices' history an evaluation at time t uses
const std::vector<History>& spatial_history_for(JointState& s, const Params& a, const SpatialInput& in, double t) {
    if (!s.started || t < s.sprev[0].time) {
        s.initial_axis = in.u;
        s.initial_axial = in.p[2];
        s.srecords.assign(in.kins.size() + in.faces.size(), std::vector<Record>());
        s.failure.clear();
        double share = 1.0 / a.slices;
        s.scur.clear();
        for (size_t k = 0; k < in.kins.size(); ++k) {
            History fresh;
            fresh.time = t;
            s.scur.push_back(accept(fresh, a, slice_accepted(in.kins[k]), t, s.srecords[k], share));
        }
        for (size_t k = 0; k < in.faces.size(); ++k) {
            History fresh;
            fresh.time = t;
            s.scur.push_back(accept(fresh, a, face_accepted(in.faces[k]), t, s.srecords[in.kins.size() + k], 1.0,
                                    true));
        }
        s.sprev = s.scur;
        s.sinitial = s.scur;
        s.started = true;
        bool finite = true;
        for (const SliceKinematics& k : in.kins) finite = finite && slice_finite(k);
        for (const FaceKinematics& k : in.faces) finite = finite && face_finite(k);
        if (!finite) {
            fail(s, t, "the state became non-finite (NaN or inf); the integration diverged");
        }
    }
    return t <= s.scur[0].time ? s.sprev : s.scur;
}

V6 spatial_force(const Params& a, double t, const V3& displacement, const V3& rotation, const V3& velocity,
                 const V3& angularVelocity) {
    JointState& s = state(a.id);
    s.force_calls++;
    SpatialInput in = spatial_kinematics(a, s, displacement, rotation, velocity, angularVelocity);
    const std::vector<History>& history = spatial_history_for(s, a, in, t);
    double share = 1.0 / a.slices;
    double loads[9] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    for (size_t i = 0; i < in.kins.size(); ++i) {
        const SliceKinematics& k = in.kins[i];
        if (k.delta <= 0.0) continue;
        double v0 = onset_velocity(history[i], k.delta, k.delta_dot);
        double f_n = share * normal_force(a, k.delta, k.delta_dot, v0);                      // eq. (41)
        double mu = a.friction_code != FRICTION_NONE ? friction_coefficient(a, k.speed) : 0.0;
        double f_t, f_a;
        slice_friction(mu, f_n, k, f_t, f_a);                                                // eq. (42)
        add_slice_loads(loads, a.r_j, in.u, k, f_n, f_t, f_a);
    }
    for (size_t i = 0; i < in.faces.size(); ++i) {  // the end faces, section 9.6
        const FaceKinematics& k = in.faces[i];
        if (k.delta <= 0.0) continue;
        double v0 = onset_velocity(history[in.kins.size() + i], k.delta, k.delta_dot);
        double f_n = face_normal_force(a.face_stiffness, a.damping_factor, a.v_min, k.delta, k.delta_dot, v0);  // eq. (53)
        double f_t = a.friction_code != FRICTION_NONE ? friction_coefficient(a, k.v_t) * f_n : 0.0;          // eq. (53)
        add_face_loads(loads, a.friction_radius, in.u, k, f_n, f_t);                                        // eq. (54)
    }
    V3 force{loads[0], loads[1], loads[2]};
    V3 pf = cross(in.p, force);                                                              // eq. (45)
    s.torque_correction3 = V3{pf[0] + loads[6], pf[1] + loads[7], pf[2] + loads[8]};
    return V6{loads[0], loads[1], loads[2], loads[3], loads[4], loads[5]};
}

V6 force_torque(const MainSystem&, double t, int, V3 displacement, V3 rotation, V3 velocity, V3 angularVelocity,
                M6 parameters, M6, M3, M3, V6) {
    Params a = decode(parameters);
    switch (a.role) {
        case PROBE: {  // marker 0 the bearing, marker 1 the ground: minus the bearing's spin in J0
            JointState& s = state(a.id);
            s.omega_bearing = -angularVelocity[2];
            s.omega_bearing3 = V3{-angularVelocity[0], -angularVelocity[1], -angularVelocity[2]};
            return zeros6();
        }
        case TORQUE: {
            const JointState& s = state(a.id);
            if (a.slices > 0) {
                return V6{0.0, 0.0, 0.0, s.torque_correction3[0], s.torque_correction3[1], s.torque_correction3[2]};
            }
            return V6{0.0, 0.0, 0.0, 0.0, 0.0, s.torque_correction};
        }
        default:
            if (a.slices > 0) return spatial_force(a, t, displacement, rotation, velocity, angularVelocity);
            return main_force(a, t, displacement, velocity, angularVelocity);
    }
}

// Error a post-Newton function returns to make Exudyn redo a step (above its
// discontinuous.iterationTolerance, default 1).
const double REDO_STEP_ERROR = 1e3;
// Relative slack on a step length compared with impact_step (Exudyn's steps carry round-off).
const double STEP_SLACK = 1e-9;
// Entries of the data node (exuclear/engine/layout.py DATA_COLUMNS).
const int N_DATA = 14;

// Appends a history's data-node entries (layout.DATA_COLUMNS) from entry `first` on.
void write_data(const History& h, StdVector& out, int first = 0) {
    double values[N_DATA] = {h.time, h.delta == -INF ? 0.0 : h.delta, h.delta_dot, h.ex, h.ey, h.f_n, h.f_t, h.v_t,
                             h.v0, h.in_contact ? 1.0 : 0.0, static_cast<double>(h.onsets), h.onset_time,
                             h.peak_force, h.max_penetration};
    for (int i = first; i < N_DATA; ++i) out.push_back(values[i]);
}

std::string fmt(double x) {
    std::ostringstream o;
    o.precision(4);
    o << x;
    return o.str();
}

// SpatialJointKernel.post_newton: the slices' history update, once per accepted step
StdVector spatial_post_newton(const Params& a, double t, const StdVector& data, const V3& displacement,
                              const V3& rotation, const V3& velocity, const V3& angularVelocity) {
    StdVector out{0.0, -1.0};
    JointState& s = state(a.id);
    s.post_newton_calls++;
    SpatialInput in = spatial_kinematics(a, s, displacement, rotation, velocity, angularVelocity);
    spatial_history_for(s, a, in, t);  // starts a run if needed
    bool advance = t > s.scur[0].time;
    const std::vector<History>& base = advance ? s.scur : s.sprev;  // a repeated step starts again from its start
    double deepest = -INF;
    bool finite = true;
    for (const SliceKinematics& k : in.kins) finite = finite && slice_finite(k);
    for (const FaceKinematics& k : in.faces) finite = finite && face_finite(k);
    if (!finite) {
        fail(s, t, "the state became non-finite (NaN or inf); the integration diverged");
    }
    for (const SliceKinematics& k : in.kins) deepest = k.delta > deepest ? k.delta : deepest;
    for (const FaceKinematics& k : in.faces) deepest = k.delta > deepest ? k.delta : deepest;
    if (deepest > a.max_penetration) {
        fail(s, t, "penetration " + fmt(deepest) + " m exceeds the limit " + fmt(a.max_penetration) + " m");
    }
    if (a.impact_step > 0.0 && t - base[0].time > a.impact_step * (1.0 + STEP_SLACK)) {
        for (size_t i = 0; i < in.kins.size() + in.faces.size(); ++i) {
            double delta = i < in.kins.size() ? in.kins[i].delta : in.faces[i - in.kins.size()].delta;
            if (!base[i].in_contact && delta > 0.0) {
                out[0] = REDO_STEP_ERROR;  // a contact begins in a long step: redo it with impact_step
                out[1] = a.impact_step;
                out.insert(out.end(), data.begin(), data.end());
                return out;
            }
        }
    }
    double share = 1.0 / a.slices;
    std::vector<History> next;
    size_t n_slices = in.kins.size();
    next.reserve(n_slices + in.faces.size());
    for (size_t i = 0; i < n_slices + in.faces.size(); ++i) {
        s.srecords[i].resize(static_cast<size_t>(base[i].closed));
        History h = i < n_slices ? accept(base[i], a, slice_accepted(in.kins[i]), t, s.srecords[i], share)
                                 : accept(base[i], a, face_accepted(in.faces[i - n_slices]), t, s.srecords[i], 1.0,
                                          true);
        if (!std::isfinite(h.f_n)) {
            fail(s, t, "the contact force became non-finite (NaN or inf)");
        }
        next.push_back(h);
    }
    if (advance) s.sprev = s.scur;  // base is not read after this
    s.scur = std::move(next);
    out.push_back(t);  // spatial_data_values
    out.push_back(in.u[0]);
    out.push_back(in.u[1]);
    out.push_back(in.p[2]);
    out.reserve(out.size() + s.scur.size() * (N_DATA - 1));
    for (const History& h : s.scur) write_data(h, out, 1);  // each contact's entries without its time
    return out;
}

// Post-Newton function: once per accepted step, the history update (mirrors
// _python_kernel.PythonJointKernel.post_newton).  Returns [error, recommended step, data...].
StdVector post_newton(const MainSystem&, double t, int, StdVector data, V3 displacement, V3 rotation, V3 velocity,
                      V3 angularVelocity, M6 parameters, M6, M3, M3, V6) {
    Params a = decode(parameters);
    StdVector out{0.0, -1.0};
    if (a.role == PROBE) {
        JointState& s = state(a.id);
        s.omega_bearing = -angularVelocity[2];
        s.omega_bearing3 = V3{-angularVelocity[0], -angularVelocity[1], -angularVelocity[2]};
        out.insert(out.end(), data.begin(), data.end());
        return out;
    }
    if (a.slices > 0) return spatial_post_newton(a, t, data, displacement, rotation, velocity, angularVelocity);
    JointState& s = state(a.id);
    s.post_newton_calls++;
    double omega_j = s.omega_bearing;
    double omega_i = angularVelocity[2] + omega_j;
    Kinematics k = contact_kinematics(a, displacement[0], displacement[1], velocity[0], velocity[1], omega_i, omega_j);
    history_for(s, a, k, t);  // starts a run if needed
    bool advance = t > s.cur.time;
    const History base = advance ? s.cur : s.prev;  // a repeated step starts again from its start
    if (!(std::isfinite(k.ex) && std::isfinite(k.ey) && std::isfinite(k.delta_dot) && std::isfinite(k.v_t))) {
        fail(s, t, "the state became non-finite (NaN or inf); the integration diverged");
    }
    if (k.delta > a.max_penetration) {
        fail(s, t, "penetration " + fmt(k.delta) + " m exceeds the limit " + fmt(a.max_penetration) + " m");
    }
    if (a.impact_step > 0.0 && !base.in_contact && k.delta > 0.0 &&
        t - base.time > a.impact_step * (1.0 + STEP_SLACK)) {
        out[0] = REDO_STEP_ERROR;  // a contact begins in a long step: redo it with impact_step
        out[1] = a.impact_step;
        out.insert(out.end(), data.begin(), data.end());
        return out;
    }
    s.records.resize(static_cast<size_t>(base.closed));
    History next = accept(base, a, k, t, s.records);
    if (!std::isfinite(next.f_n)) {
        fail(s, t, "the contact force became non-finite (NaN or inf)");
    }
    if (advance) s.prev = s.cur;
    s.cur = next;
    write_data(next, out);
    return out;
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
    return d;
}

}  // namespace

PYBIND11_MODULE(_ckernel, m) {
    m.doc() = "Compiled kernel of the exuclear clearance joint (see exuclear/engine/kernel.py)";
    m.def("force_torque", &force_torque, py::call_guard<DispatchCounter>(),
          "springForceTorqueUserFunction of the clearance-joint connectors");
    m.def("post_newton", &post_newton, py::call_guard<DispatchCounter>(),
          "postNewtonStepUserFunction of the clearance-joint connectors");
    m.def("new_joint", []() {
        g_joints.emplace_back();
        return static_cast<long>(g_joints.size() - 1);
    });
    m.def("reset", [](long id) { state(id) = JointState(); });
    m.def("dispatch_calls", []() { return g_dispatch_calls; });
    m.def("calls", [](long id) {
        JointState& s = state(id);
        return py::make_tuple(s.force_calls, s.post_newton_calls);
    });
    m.def("history", [](long id) {
        JointState& s = state(id);
        py::dict d;
        d["started"] = s.started;
        d["current"] = history_dict(s.cur);
        d["previous"] = history_dict(s.prev);
        d["initial"] = history_dict(s.initial);
        return d;
    });
    m.def("records", [](long id) {
        JointState& s = state(id);
        py::list out;
        for (const Record& r : s.records) {
            out.append(py::make_tuple(r.onset_time, r.onset_velocity, r.peak_force, r.duration, r.max_penetration));
        }
        return out;
    });
    m.def("slice_history", [](long id) {
        JointState& s = state(id);
        py::dict d;
        for (const char* which : {"current", "previous", "initial"}) {
            const std::vector<History>& hs = std::string(which) == "current"    ? s.scur
                                             : std::string(which) == "previous" ? s.sprev
                                                                                : s.sinitial;
            py::list l;
            for (const History& h : hs) l.append(history_dict(h));
            d[which] = l;
        }
        return d;
    });
    m.def("slice_records", [](long id) {
        JointState& s = state(id);
        py::list out;
        for (const std::vector<Record>& rs : s.srecords) {
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
    m.attr("N_DATA") = N_DATA;
    m.attr("STIFFNESS_CODES") = STIFFNESS_CODES;
}
