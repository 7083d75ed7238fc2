// The rules of the field table (schema.hpp) applied to a value, in the words of validation.hpp.
#include <cmath>
#include <string>

#include "anyphys/checks.hpp"
#include "anyphys/error.hpp"
#include "anyphys/schema.hpp"

namespace anyphys::schema {

namespace {
// One scalar against a scalar rule, with the wording of validation.cpp.
void checkNumber(Check check, double bound, std::string_view words, const std::string& field, double v) {
    using namespace anyphys::detail;
    switch (check) {
        case Check::Finite: requireFinite(field, v); break;
        case Check::Positive: requirePositive(field, v); break;
        case Check::NonNegative: requireNonNegative(field, v); break;
        case Check::UnitInterval:
            if (!(std::isfinite(v) && v >= 0 && v <= 1)) throw Error::invalid(field, v, "must be in [0, 1]");
            break;
        case Check::Within:
            requireFinite(field, v);
            if (std::abs(v) > bound) throw Error::invalid(field, v, "must be within +-" + ceilingText(bound));
            break;
        case Check::Coordinate: requireCoordinate(field, v); break;
        case Check::Length: requireLength(field, v); break;
        case Check::LengthOrZero: requireLength(field, v, true); break;
        case Check::TimeStep: requireTimeStep(field, v); break;
        case Check::PositiveAtMost:
            requirePositive(field, v);
            if (v > bound) throw Error::invalid(field, v, "must be <= " + ceilingText(bound) + std::string(words));
            break;
        case Check::Threshold:
            if (!(v > 0)) throw Error::invalid(field, v, "must be > 0" + std::string(words));
            break;
        default: break;
    }
}
}  // namespace

void checkValue(Check check, double bound, std::string_view words, const Value& value, const std::string& field) {
    using namespace anyphys::detail;
    if (const double* d = std::get_if<double>(&value)) return checkNumber(check, bound, words, field, *d);
    if (const int* n = std::get_if<int>(&value)) {
        if (check == Check::CountIn && (*n < 1 || *n > bound))
            throw Error::invalid(field, *n, "must be in [1, " + std::to_string(static_cast<int>(bound)) + "]" + std::string(words));
        return;
    }
    if (const Vec3* v = std::get_if<Vec3>(&value)) {
        switch (check) {
            case Check::Finite: return requireFinite(field, *v);
            case Check::Coordinate: return requireCoordinate(field, *v);
            case Check::Magnitude:
                requireFinite(field, *v);
                if (v->norm() > bound)
                    throw Error::invalid(field, formatVec3(*v), "magnitude must be <= " + ceilingText(bound) + std::string(words));
                return;
            case Check::Direction:
                requireFinite(field, *v);
                if (v->norm() < 1e-12) throw Error::invalid(field, formatVec3(*v), "must be non-zero");
                return;
            default:
                for (int i = 0; i < 3; ++i) checkNumber(check, bound, words, field + "[" + std::to_string(i) + "]", (*v)[i]);
                return;
        }
    }
    if (const Quat* q = std::get_if<Quat>(&value)) {
        if (check == Check::UnitQuaternion &&
            (!q->coeffs().allFinite() || std::abs(q->norm() - 1.0) > kUnitQuaternionTolerance))
            throw Error::invalid(field, formatQuat(*q), "must be a unit quaternion [w, x, y, z] (norm 1 within 1e-4)");
        return;
    }
    if (const std::string* s = std::get_if<std::string>(&value))
        if (check == Check::NonEmpty && s->empty()) throw Error::invalid(field, "\"\"", std::string(words));
}

}  // namespace anyphys::schema
