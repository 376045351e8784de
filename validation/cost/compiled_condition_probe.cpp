// The probe module of validation/cost/compiled_condition.py: a condition on a mass point in
// the plane, |p| = 1 at position level or n . v = 0 at velocity level (n = p / |p|), as
// Exudyn's ObjectConnectorCoordinateVector constraintUserFunction and jacobianUserFunction,
// whose C++ signatures are
//   std::vector<double>(const MainSystem&, double t, int item, std::vector<double> q,
//                       std::vector<double> q_t, bool velocityLevel)
//   py::object(const MainSystem&, double t, int item, std::vector<double> q,
//              std::vector<double> q_t, bool velocityLevel)
// (q: the coordinates of the connector's two markers in turn; here marker 0 is a ground
// node with none).  Counts its calls, and the calls that came through pybind11's Python
// dispatcher (as the kernel's self-test does, exuclear/_kernel/bindings.cpp).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <vector>

#include "layout.hpp"  // exuclear/_kernel: Exudyn's MainSystem and its pybind11 type caster

namespace py = pybind11;

namespace {
long g_dispatch_calls = 0, g_constraint_calls = 0, g_jacobian_calls = 0;
struct DispatchCounter {  // constructed only when a call comes through pybind11's Python dispatcher
    DispatchCounter() { ++g_dispatch_calls; }
};
}  // namespace

namespace {
std::vector<double> constraint(const MainSystem&, double, int, std::vector<double> q, std::vector<double> q_t,
                               bool velocity_level) {
    ++g_constraint_calls;
    const double r = std::hypot(q[0], q[1]);
    if (velocity_level) return {(q[0] * q_t[0] + q[1] * q_t[1]) / r};
    return {r - 1.0};
}

py::object jacobian(const MainSystem&, double, int, std::vector<double> q, std::vector<double>, bool) {
    ++g_jacobian_calls;
    const double r = std::hypot(q[0], q[1]);
    py::array_t<double> rows({1, 2});
    auto m = rows.mutable_unchecked<2>();
    m(0, 0) = q[0] / r;
    m(0, 1) = q[1] / r;
    return std::move(rows);
}
}  // namespace

PYBIND11_MODULE(compiled_condition_probe, m) {
    m.def("constraint", &constraint, py::call_guard<DispatchCounter>());
    m.def("jacobian", &jacobian, py::call_guard<DispatchCounter>());
    m.def("counts", []() { return py::make_tuple(g_dispatch_calls, g_constraint_calls, g_jacobian_calls); });
}
