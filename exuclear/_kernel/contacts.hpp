// One contact: its history (exuclear/history.py), its response (onset velocity, normal force,
// friction; the same for slices, end faces and the ball) and its loads (exuclear/spatial.py, eqs.
// (41)-(45), (54); exuclear/spherical.py, eqs. (97), (98)).  Python: exuclear/engine/_python_kernel/contacts.py.

#pragma once

#include "laws.hpp"

namespace {

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

// ---- one contact: _python_kernel/contacts.py's Contact classes ----------------------------------------
// A revolute joint's contacts are its slices (one for the planar joint), then its two end faces
// where it has an axial clearance; a spherical joint's is its ball.  The kind decides the
// stiffness, the slip friction acts against and where the loads go; response() is the same for all.
enum ContactKind {
    PLANAR_SLICE,  // the planar joint's one slice: the joint's law, slip v_T (eqs. (9), (20))
    SLICE,         // a spatial slice: its share w / L of the law, slip |v_s| (eqs. (41), (42))
    FACE,          // an end face: flat-punch stiffness K_f, slip at the friction radius (eq. (53))
    BALL,          // the spherical joint's ball: the joint's law, slip |v_s| across the normal (eq. (96))
    CORNER,        // a slider's corner against a guide's wall: the joint's law, slip v_t along the wall
    BOX_CORNER,    // the spatial slider's corner against a channel's wall: the joint's law, slip |v_s| over the wall
    SLOT_SLICE     // the pin-in-slot joint's slice: the planar slice against the slot's centre segment
};

int slice_count(const Params& a) { return a.slices > 0 ? a.slices : 1; }

// the planar revolute joint (one slice, the motion projected on the plane normal to the axis)
bool planar(const Params& a) { return (a.joint_type == REVOLUTE || a.joint_type == PIN_SLOT) && a.slices == 0; }

// the spatial translational joint: a box in a channel (prismatic.py GuideGeometry.spatial)
bool box(const Params& a) { return a.joint_type == PRISMATIC && a.half_width > 0.0; }

size_t contact_count(const Params& a) {
    if (box(a)) return static_cast<size_t>(N_BOX_CORNERS * N_BOX_WALLS);  // prismatic.py BOX_PAIRS
    if (a.joint_type == PRISMATIC) return static_cast<size_t>(N_CORNERS * N_WALLS);  // prismatic.py PAIRS
    return static_cast<size_t>(slice_count(a)) + (a.play > 0.0 ? 2u : 0u);
}

ContactKind contact_kind(const Params& a, size_t i) {
    if (a.joint_type == SPHERICAL) return BALL;
    if (a.joint_type == PRISMATIC) return box(a) ? BOX_CORNER : CORNER;
    if (a.joint_type == PIN_SLOT) return SLOT_SLICE;
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

// contacts.py SlotSlice.add_loads: joint_loads, and the slot's moment S x (-F_i) about its centre
void slot_loads(double* loads, double r_j, double r_b, const Kinematics& k, double f_n, double f_t) {
    joint_loads(loads, r_j, r_b, k, f_n, f_t);
    double fy = -f_n * k.ny + f_t * k.nx;                                // F_i's y, eq. (24)
    loads[8] -= k.segment * fy;
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

// spherical.py add_ball_loads: the ball's loads = [force (3), torque (3), correction (3)]
void add_ball_loads(double* loads, double r_b, const Kinematics& k, double f_n, double f_t) {
    V3 t_force{0.0, 0.0, 0.0};
    if (k.v_t > 0.0) {
        double scale = f_t / k.v_t;
        t_force = V3{scale * k.v_s[0], scale * k.v_s[1], scale * k.v_s[2]};  // friction on the socket, eq. (97)
    }
    V3 total{f_n * k.nx + t_force[0], f_n * k.ny + t_force[1], f_n * k.nz + t_force[2]};
    V3 rim = cross(V3{r_b * k.nx, r_b * k.ny, r_b * k.nz}, t_force);
    V3 couple = cross(V3{k.delta * k.nx, k.delta * k.ny, k.delta * k.nz}, t_force);
    for (int i = 0; i < 3; ++i) {
        loads[i] += total[i];                                           // eq. (97)
        loads[3 + i] += rim[i];                                         // eq. (98)
        loads[6 + i] -= couple[i];                                      // eq. (98), p x F added at the end
    }
}

// prismatic.py add_corner_loads: on the guide F = F_N n + F_T x, T = r x F; p x F added at the end
void add_corner_loads(double* loads, const Kinematics& k, double f_n, double f_t) {
    double fx = f_t + f_n * k.nx;
    double fy = f_n * k.ny;
    loads[0] += fx;
    loads[1] += fy;
    loads[5] += k.rx * fy - k.ry * fx;                                  // T = -(r x (-F)) = r x F
}

// prismatic.py add_box_corner_loads: on the guide F = F_N n + F_T v_s / |v_s|, T = r x F; p x F added at the end
void add_box_corner_loads(double* loads, const Kinematics& k, double f_n, double f_t) {
    V3 t_force{0.0, 0.0, 0.0};
    if (k.v_t > 0.0) {
        double scale = f_t / k.v_t;
        t_force = V3{scale * k.v_s[0], scale * k.v_s[1], scale * k.v_s[2]};
    }
    V3 force{f_n * k.nx + t_force[0], f_n * k.ny + t_force[1], f_n * k.nz + t_force[2]};
    V3 moment = cross(V3{k.rx, k.ry, k.rz}, force);
    for (int i = 0; i < 3; ++i) {
        loads[i] += force[i];
        loads[3 + i] += moment[i];
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
        case BALL:  // eqs. (97), (98)
            add_ball_loads(loads, a.r_j, k, r.f_n, r.f_t);
            break;
        case CORNER:
            add_corner_loads(loads, k, r.f_n, r.f_t);
            break;
        case BOX_CORNER:
            add_box_corner_loads(loads, k, r.f_n, r.f_t);
            break;
        case SLOT_SLICE:  // eqs. (24)-(26) at the segment's point
            slot_loads(loads, a.r_j, a.r_b, k, r.f_n, r.f_t);
            break;
    }
}

}  // namespace
