#pragma once
// The helpers that build field rows (schema.hpp): a row's accessors from a member pointer. Only the
// files that define tables include this (api/src/schema/, fields/src/schema/), so the accessors'
// std::function objects are instantiated there and nowhere else.
#include <optional>
#include <type_traits>
#include <utility>

#include "anyphys/enums.hpp"
#include "anyphys/schema.hpp"

namespace anyphys::schema {

/// Getter and setter of a member, for the `get` and `set` of a row.
template <class Def>
struct Access {
    std::function<Value(const Def&)> get;
    std::function<bool(Def&, const Value&)> set;
};

namespace detail {
template <class T> struct IsOptional : std::false_type {};
template <class T> struct IsOptional<std::optional<T>> : std::true_type { using type = T; };

template <class T>
Value toValue(const T& v) {
    if constexpr (std::is_enum_v<T>) return std::string(toString(v));
    else return v;
}
template <class T>
bool fromValue(const Value& v, T& out) {
    if constexpr (std::is_enum_v<T>) {
        const auto e = fromString<T>(std::get<std::string>(v));
        if (e) out = *e;
        return e.has_value();
    } else {
        out = std::get<T>(v);
        return true;
    }
}
}  // namespace detail

/// The accessors of a plain or optional member (enums through their names).
template <class Def, class M>
Access<Def> member(M Def::*m) {
    if constexpr (detail::IsOptional<M>::value) {
        using T = typename detail::IsOptional<M>::type;
        return {[m](const Def& d) -> Value { return d.*m ? detail::toValue(*(d.*m)) : Value{}; },
                [m](Def& d, const Value& v) {
                    if (std::holds_alternative<std::monostate>(v)) return (d.*m).reset(), true;
                    T out{};
                    if (!detail::fromValue(v, out)) return false;
                    d.*m = out;
                    return true;
                }};
    } else {
        return {[m](const Def& d) -> Value { return detail::toValue(d.*m); },
                [m](Def& d, const Value& v) { return detail::fromValue(v, d.*m); }};
    }
}

/// A row with the accessors of `access` (a designated-initialiser row cannot take them from a helper).
template <class Def>
Field<Def> with(Field<Def> row, Access<Def> access, std::string (*allowed)() = nullptr) {
    row.get = std::move(access.get);
    row.set = std::move(access.set);
    row.allowed = allowed;
    return row;
}

}  // namespace anyphys::schema
