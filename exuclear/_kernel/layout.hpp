// The parameters of a clearance joint as its connector's `stiffness` matrix carries them
// (exuclear/engine/layout.py LAYOUT, field by field: Params and decode), and the size of its
// data node (layout.py DATA_COLUMNS, FILM_DATA_COLUMNS).  Python: exuclear/engine/layout.py and
// exuclear/engine/_python_kernel/layout.py.  Also Exudyn's MainSystem as the signatures name it.

#pragma once

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

class MainSystem;  // Exudyn's; only its name enters the signatures, it is never dereferenced

// Lets pybind11 bind functions that take Exudyn's MainSystem, which this module does not
// know (the kernel's bindings.cpp).
// A call from Python (a self-test's fallback check) passes any object; the functions never
// touch it.
namespace pybind11 {
namespace detail {
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
// layout.py JOINT_TYPE_CODES: which contacts a joint has (joint_state.hpp joint_kinematics)
enum JointType { REVOLUTE = 0, SPHERICAL = 1, PRISMATIC = 2, PIN_SLOT = 3 };

// layout.py WEAR_SURFACE_CODES and WEAR_PRESSURE_CODES, packed in the field wear_code
enum WearSurface { WEAR_NONE = 0, WEAR_BEARING = 1, WEAR_JOURNAL = 2, WEAR_BOTH = 3 };
enum WearPressure { WEAR_WINKLER = 0, WEAR_HERTZ = 1 };

// The fields of the connector's `stiffness` matrix, in the order of layout.py's LAYOUT; a
// test compares this table (exported as the module's LAYOUT) with layout.py's.
enum Field {
    JOINT_ID, ROLE, JOINT_TYPE, INNER_RADIUS, OUTER_RADIUS, MAX_PENETRATION,
    IMPACT_STEP, STIFFNESS_CODE, DAMPING_FACTOR, V_MIN, FRICTION_CODE,
    STIFFNESS_CONSTANTS, FRICTION_CONSTANTS,
    SLICES, LENGTH, AXIS_JOURNAL,
    AXIAL_CLEARANCE, FRICTION_RADIUS, FACE_STIFFNESS,
    FILM_MODEL, VISCOSITY, EPS_FILM, EPS_CAP,
    RATE_LIMIT, BEARING_MOTION,
    WEAR_CODE, WEAR_COEFFICIENT,
    N_FIELDS
};

struct FieldPosition {
    const char* name;
    int row, column, size;
};

constexpr FieldPosition LAYOUT[N_FIELDS] = {
    {"joint_id", 0, 0, 1},        {"role", 0, 1, 1},           {"joint_type", 0, 2, 1},
    {"inner_radius", 0, 3, 1},    {"outer_radius", 0, 4, 1},   {"max_penetration", 0, 5, 1},
    {"impact_step", 1, 0, 1},     {"stiffness_code", 1, 1, 1}, {"damping_factor", 1, 2, 1},
    {"v_min", 1, 3, 1},           {"friction_code", 1, 4, 1},
    {"stiffness_constants", 2, 0, 5},
    {"friction_constants", 3, 0, 4},
    {"slices", 4, 0, 1},          {"length", 4, 1, 1},         {"axis_journal", 4, 2, 3},
    {"axial_clearance", 5, 0, 1}, {"friction_radius", 5, 1, 1}, {"face_stiffness", 5, 2, 1},
    {"film_model", 3, 4, 1},      {"viscosity", 3, 5, 1},
    {"eps_film", 5, 4, 1},        {"eps_cap", 5, 5, 1},
    {"rate_limit", 1, 5, 1},      {"bearing_motion", 4, 5, 1},
    {"wear_code", 2, 5, 1},       {"wear_coefficient", 5, 3, 1},
};

double field(const M6& p, Field f, int i = 0) { return p[LAYOUT[f].row][LAYOUT[f].column + i]; }

// The fields of the connector's `damping` matrix (layout.py SECOND_LAYOUT): the handle's mark and
// what a joint type needs where the `stiffness` matrix has no free entry; 0 is each field's default.
enum SecondField { TOKEN, GUIDE_LENGTH, SLIDER_HALF_WIDTH, CHANNEL_HALF_WIDTH, N_SECOND_FIELDS };

constexpr FieldPosition SECOND_LAYOUT[N_SECOND_FIELDS] = {
    {"token", 0, 0, 1}, {"guide_length", 0, 1, 1}, {"slider_half_width", 0, 2, 1}, {"channel_half_width", 0, 3, 1},
};

double second_field(const M6& d, SecondField f) { return d[SECOND_LAYOUT[f].row][SECOND_LAYOUT[f].column]; }

struct Params {
    long id;
    int role;
    JointType joint_type;
    double r_j, r_b;  // the contact pair's inner and outer radius (journal and bearing, ball and socket)
    double max_penetration, impact_step;
    int stiffness_code;
    double damping_factor, v_min;
    int friction_code;
    double kp[5];
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
    // a planar joint's wear (section 11), from layout.py wear_code: which surfaces (WEAR_NONE:
    // none), the pressure over the arc, the profiles' nodes; and k_D [1/Pa]
    int wear_surface, wear_pressure, wear_nodes;
    double wear_coefficient;
    // a translational joint's (the damping matrix, SECOND_LAYOUT): half the guide's length (INF:
    // its walls do not end), the spatial slider's half-width B/2 (0: the planar joint) and its
    // channel's half-depth B/2 + c_z
    double half_guide, half_width, channel_half_width;
};

// The parameters of the `stiffness` matrix p and the `damping` matrix d (zeros: every second
// field at its default).
Params decode(const M6& p, const M6& d = M6{}) {
    Params a;
    a.id = static_cast<long>(field(p, JOINT_ID));
    a.role = static_cast<int>(field(p, ROLE));
    a.joint_type = static_cast<JointType>(static_cast<int>(field(p, JOINT_TYPE)));
    a.r_j = field(p, INNER_RADIUS);
    a.r_b = field(p, OUTER_RADIUS);
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
    double code = field(p, WEAR_CODE);  // surface + 4 pressure + 8 nodes (layout.py wear_code); 0: no wear
    if (code == 0.0) {  // the unworn joint: no integer divisions in its every evaluation
        a.wear_surface = WEAR_NONE;
        a.wear_pressure = WEAR_WINKLER;
        a.wear_nodes = 0;
    } else {
        long wear = static_cast<long>(code);
        a.wear_surface = static_cast<int>(wear % 4);
        a.wear_pressure = static_cast<int>((wear / 4) % 2);
        a.wear_nodes = static_cast<int>(wear / 8);
    }
    a.wear_coefficient = field(p, WEAR_COEFFICIENT);
    double guide_length = second_field(d, GUIDE_LENGTH);
    a.half_guide = guide_length > 0.0 ? 0.5 * guide_length : INF;
    a.half_width = second_field(d, SLIDER_HALF_WIDTH);
    a.channel_half_width = second_field(d, CHANNEL_HALF_WIDTH);
    return a;
}

// Entries of the data node (exuclear/engine/layout.py DATA_COLUMNS), and a lubricated joint's
// film entries after them (FILM_DATA_COLUMNS).
const int N_DATA = 14;
const int N_FILM_DATA = 3;

}  // namespace
