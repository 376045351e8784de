// The contact kinematics of a slice, the planar joint, an end face and the spherical joint's ball:
// exuclear/geometry.py, exuclear/spatial.py and exuclear/spherical.py (docs/physics.md eqs. (1)-(8),
// (33)-(40), (48)-(51), (93)-(96)).  Python:
// exuclear/engine/_python_kernel/kinematics.py.

#pragma once

#include "layout.hpp"

namespace {

// ---- physics: geometry.py and spatial.py (docs/physics.md eqs. (1)-(8), (33)-(40), (48)-(51)) --
V3 cross(const V3& a, const V3& b) {
    return V3{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

double slice_centre(double length, int slices, int k) {  // eq. (33): the centre of slice k
    double width = length / slices;
    return -0.5 * length + (k + 0.5) * width;
}

V3 turn(const M3& a, const V3& x) { return V3{dot(a[0], x), dot(a[1], x), dot(a[2], x)}; }  // A x

// Tait-Bryan angles: A = Rx(a) Ry(b) Rz(c), as Exudyn's RotXYZ2RotationMatrix
M3 rotation_xyz(double a, double b, double c) {
    double ca = std::cos(a), sa = std::sin(a), cb = std::cos(b), sb = std::sin(b), cc = std::cos(c), sc = std::sin(c);
    return M3{V3{cb * cc, -cb * sc, sb}, V3{ca * sc + sa * sb * cc, ca * cc - sa * sb * sc, -sa * cb},
              V3{sa * sc - ca * sb * cc, sa * cc + ca * sb * sc, ca * cb}};
}

V3 journal_axis(const V3& angles, const V3& axis_journal) {  // eq. (34): Rx(a) Ry(b) Rz(c) a_J
    return turn(rotation_xyz(angles[0], angles[1], angles[2]), axis_journal);
}

// One contact's kinematics: spatial.py's SliceKinematics (side 0) or FaceKinematics (side -1, +1),
// or spherical.py's BallKinematics (ez, nz and the slip vector v_s; v_t its length), or
// prismatic.py's CornerKinematics (rx, ry the corner relative to the slider's centre) or
// BoxCornerKinematics (ez, nz, the slip v_s with v_t its length, rx, ry, rz its r), or
// slot.py's SlotKinematics (segment: the x of the slot's centre-segment point under the pin)
struct Kinematics {
    int side;
    double s, ex, ey, ecc, nx, ny, a, delta, delta_dot, v_t, v_a, speed;
    double ez, nz;
    V3 v_s;
    double rx, ry, rz;
    double segment;
};

// geometry.py kinematics_along: the rest of contact_kinematics once |e| (ecc) and the normal
// (nx, ny) are known; a worn joint's contact gives its own (wear.hpp WearState::kinematics).
Kinematics kinematics_along(double r_j, double r_b, double ex, double ey, double ecc, double nx, double ny, double dvx,
                            double dvy, double omega_i, double omega_j) {
    Kinematics k{};
    k.side = 0;
    k.ex = ex;
    k.ey = ey;
    k.ecc = ecc;
    k.nx = nx;
    k.ny = ny;
    k.delta_dot = dvx * k.nx + dvy * k.ny;                                             // eq. (7)
    k.v_t = dvx * k.ny - dvy * k.nx - omega_i * r_j + omega_j * r_b;                   // eq. (8)
    k.delta = k.ecc - (r_b - r_j);                                                     // eq. (4)
    k.speed = std::fabs(k.v_t);
    return k;
}

// geometry.py contact_kinematics, eqs. (1)-(8): the planar joint's one slice.  The spatial
// slice's eqs. (35)-(40) reduce to these for the motion projected on the plane normal to the
// axis (s = 0, m = n, w_j x p normal to n); they are evaluated in this reduced form, in both
// kernels, so that the planar joint keeps its results bit for bit (some scenes, e.g. a 3D
// double pendulum at a coarse fixed step, change course on a last-bit change of the force).
// (ex, ey) the eccentricity, (dvx, dvy) the relative velocity, omega_i, omega_j the journal's and
// the bearing's spin about the axis.
Kinematics contact_kinematics(double r_j, double r_b, double ex, double ey, double dvx, double dvy, double omega_i,
                              double omega_j) {
    double ecc = std::sqrt(ex * ex + ey * ey);
    if (ecc > 0.0) return kinematics_along(r_j, r_b, ex, ey, ecc, ex / ecc, ey / ecc, dvx, dvy, omega_i, omega_j);
    // centred journal: no contact, any normal keeps the values finite
    return kinematics_along(r_j, r_b, ex, ey, ecc, 1.0, 0.0, dvx, dvy, omega_i, omega_j);
}

// spatial.py slice_kinematics_along: the rest of slice_kinematics once |e| (ecc) and the in-plane
// normal (nx, ny) are known (eqs. (36)-(40)); a worn slice gives its own (the worn contact's
// normal, eq. (75), and ecc = delta + c from its penetration, eq. (76); wear.hpp
// WearState::slice_kinematics), as kinematics_along for the planar joint
Kinematics slice_kinematics_along(double r_j, double r_b, double s, double ex, double ey, double ecc, double nx,
                                  double ny, const V3& p, const V3& u, const V3& dv, const V3& dw, const V3& w_j) {
    Kinematics k;
    k.side = 0;
    k.s = s;
    k.ex = ex;
    k.ey = ey;
    k.ecc = ecc;
    k.nx = nx;
    k.ny = ny;
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

// spatial.py slice_kinematics, eqs. (35)-(40): the eccentricity of the slice plane z (eq. (35),
// spatial.py slice_eccentricity), its direction the normal
Kinematics slice_kinematics(double r_j, double r_b, double z, const V3& p, const V3& u, const V3& dv, const V3& dw,
                            const V3& w_j) {
    double s = (z - p[2]) / u[2];                                       // eq. (35)
    double ex = p[0] + s * u[0];
    double ey = p[1] + s * u[1];
    double ecc = std::sqrt(ex * ex + ey * ey);
    if (ecc > 0.0) return slice_kinematics_along(r_j, r_b, s, ex, ey, ecc, ex / ecc, ey / ecc, p, u, dv, dw, w_j);
    // journal axis on the bearing axis: no contact, any normal keeps the values finite
    return slice_kinematics_along(r_j, r_b, s, ex, ey, ecc, 1.0, 0.0, p, u, dv, dw, w_j);
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

// spherical.py ball_kinematics, eqs. (93)-(96): the ball of radius r_b in the socket of radius r_s
Kinematics ball_kinematics(double r_b, double r_s, const V3& p, const V3& dv, const V3& dw, const V3& w_j) {
    Kinematics k{};
    k.ecc = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    V3 n{1.0, 0.0, 0.0};  // the ball at the socket's centre: no contact, any normal keeps the values finite
    if (k.ecc > 0.0) n = V3{p[0] / k.ecc, p[1] / k.ecc, p[2] / k.ecc};  // eq. (93)
    k.delta = k.ecc - (r_s - r_b);                                      // eq. (94)
    k.delta_dot = n[0] * dv[0] + n[1] * dv[1] + n[2] * dv[2];           // eq. (95): the spins do not enter
    V3 r{r_b * n[0], r_b * n[1], r_b * n[2]};                            // Q_ball - P_ball
    V3 lever{k.delta * n[0] - p[0], k.delta * n[1] - p[1], k.delta * n[2] - p[2]};  // Q_ball - Q_socket - p
    V3 wr = cross(dw, r);
    V3 wl = cross(w_j, lever);
    V3 v{dv[0] + wr[0] + wl[0], dv[1] + wr[1] + wl[1], dv[2] + wr[2] + wl[2]};
    double vn = n[0] * v[0] + n[1] * v[1] + n[2] * v[2];
    k.v_s = V3{v[0] - vn * n[0], v[1] - vn * n[1], v[2] - vn * n[2]};  // eq. (96)
    k.v_t = std::sqrt(k.v_s[0] * k.v_s[0] + k.v_s[1] * k.v_s[1] + k.v_s[2] * k.v_s[2]);
    k.ex = p[0];
    k.ey = p[1];
    k.ez = p[2];
    k.nx = n[0];
    k.ny = n[1];
    k.nz = n[2];
    return k;
}

// slot.py slot_kinematics: the pin at (px, py) in the slot of half-length half_length, as the
// planar joint's slice against the segment's nearest point S; the slot's spin moves S at w_j x S
Kinematics slot_kinematics(double r_j, double r_b, double half_length, double px, double py, double dvx, double dvy,
                           double omega_i, double omega_j) {
    double sx = std::min(std::max(px, -half_length), half_length);
    Kinematics k = contact_kinematics(r_j, r_b, px - sx, py, dvx, dvy - omega_j * sx, omega_i, omega_j);
    k.segment = sx;
    return k;
}

// prismatic.py CORNER_SIGNS (as signs of L/2, H/2) and WALL_SIDES
const double CORNER_SIGNS[4][2] = {{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}};
const double WALL_SIDES[2] = {-1.0, 1.0};
const int N_CORNERS = 4;
const int N_WALLS = 2;

// prismatic.py corner_kinematics: a corner of the slider (2 half_length x 2 half_height) against
// a wall of the guide (2 half_width wide), the slider at (px, py) turned by theta in J0
Kinematics corner_kinematics(double half_length, double half_height, double half_width, int corner, int wall,
                             double px, double py, double theta, double dvx, double dvy, double dw, double w_j) {
    Kinematics k{};
    double sx = CORNER_SIGNS[corner][0], sy = CORNER_SIGNS[corner][1];
    double s = WALL_SIDES[wall];
    double cos_t = std::cos(theta), sin_t = std::sin(theta);
    k.rx = cos_t * sx * half_length - sin_t * sy * half_height;        // R(theta) c_k
    k.ry = sin_t * sx * half_length + cos_t * sy * half_height;
    k.ex = px + k.rx;                                                   // the corner in J0
    k.ey = py + k.ry;
    k.delta = s * k.ey - half_width;
    // the corner's velocity over the guide's point under it: dv + dw x r - w_j x p
    double vx = dvx - dw * k.ry + w_j * py;
    double vy = dvy + dw * k.rx - w_j * px;
    k.nx = 0.0;
    k.ny = s;
    k.delta_dot = s * vy;
    k.v_t = vx;
    return k;
}

// prismatic.py BOX_CORNER_SIGNS (as signs of L/2, H/2, B/2) and BOX_WALLS (the axis across a
// wall, the sign of its normal)
const double BOX_CORNER_SIGNS[8][3] = {{-1.0, -1.0, -1.0}, {1.0, -1.0, -1.0}, {1.0, 1.0, -1.0}, {-1.0, 1.0, -1.0},
                                       {-1.0, -1.0, 1.0},  {1.0, -1.0, 1.0},  {1.0, 1.0, 1.0},  {-1.0, 1.0, 1.0}};
const int BOX_WALL_AXES[4] = {1, 1, 2, 2};
const double BOX_WALL_SIDES[4] = {-1.0, 1.0, -1.0, 1.0};
const int N_BOX_CORNERS = 8;
const int N_BOX_WALLS = 4;

// prismatic.py box_corner_kinematics: a corner of the box (2 half_length x 2 half_height x
// 2 half_width) against a wall of the channel (walls wall_y, wall_z from its centre line), the
// box at p turned by the rotation a (rotation_xyz of the connector's angles) relative to the guide
Kinematics box_corner_kinematics(double half_length, double half_height, double half_width, double wall_y,
                                 double wall_z, int corner, int wall, const V3& p, const M3& a, const V3& dv,
                                 const V3& dw, const V3& w_j) {
    Kinematics k{};
    double sx = BOX_CORNER_SIGNS[corner][0], sy = BOX_CORNER_SIGNS[corner][1], sz = BOX_CORNER_SIGNS[corner][2];
    int axis = BOX_WALL_AXES[wall];
    double s = BOX_WALL_SIDES[wall];
    V3 c{sx * half_length, sy * half_height, sz * half_width};
    V3 r{a[0][0] * c[0] + a[0][1] * c[1] + a[0][2] * c[2],             // A c_k
         a[1][0] * c[0] + a[1][1] * c[1] + a[1][2] * c[2],
         a[2][0] * c[0] + a[2][1] * c[1] + a[2][2] * c[2]};
    V3 q{p[0] + r[0], p[1] + r[1], p[2] + r[2]};                         // the corner in J0
    k.delta = s * q[axis] - (axis == 1 ? wall_y : wall_z);
    // the corner's velocity over the guide's point under it: dv + dw x r - w_j x p
    V3 wr = cross(dw, r), wp = cross(w_j, p);
    V3 v{dv[0] + wr[0] - wp[0], dv[1] + wr[1] - wp[1], dv[2] + wr[2] - wp[2]};
    k.v_s = V3{v[0], axis == 1 ? 0.0 : v[1], axis == 2 ? 0.0 : v[2]};   // along the wall's plane
    k.v_t = std::sqrt(k.v_s[0] * k.v_s[0] + k.v_s[1] * k.v_s[1] + k.v_s[2] * k.v_s[2]);
    k.ex = q[0];
    k.ey = q[axis];
    k.ez = q[3 - axis];
    k.nx = 0.0;
    k.ny = axis == 1 ? s : 0.0;
    k.nz = axis == 2 ? s : 0.0;
    k.delta_dot = s * v[axis];
    k.rx = r[0];
    k.ry = r[1];
    k.rz = r[2];
    return k;
}

// prismatic.py leave_guide: a corner beyond the end of a guide 2 half_guide long has no wall under it
void leave_guide(Kinematics& k, double half_guide) {
    if (std::fabs(k.ex) > half_guide) k.delta = -INF;
}

bool finite(const Kinematics& k) {
    return std::isfinite(k.ex) && std::isfinite(k.ey) && std::isfinite(k.delta_dot) && std::isfinite(k.v_t);
}

}  // namespace
