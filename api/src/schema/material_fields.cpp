// The rows of Material (see schema.hpp). A material takes effect through the bodies that name it
// (`body.material`), so its rows are not capability parameters of their own.
#include <string>
#include <vector>

#include "anyphys/containers/material_library.hpp"
#include "anyphys/schema/material_fields.hpp"
#include "anyphys/schema/rows.hpp"

namespace anyphys::schema {

const std::vector<Field<Material>>& materialFields() {
    using M = Material;
    static const std::vector<Field<M>> rows = {
        with<M>({.key = "friction", .path = "material.friction", .unit = "1 (Coulomb coefficient)", .value = 0.6,
                 .check = Check::NonNegative, .honour = Honour::Parent},
                member(&M::friction)),
        with<M>({.key = "restitution", .path = "material.restitution", .unit = "1", .value = 0.0,
                 .check = Check::UnitInterval, .honour = Honour::Parent},
                member(&M::restitution)),
        with<M>({.key = "density", .path = "material.density", .unit = "kg/m^3", .value = 1000.0,
                 .check = Check::Positive, .note = "used for bodies that give neither `mass` nor `density`",
                 .honour = Honour::Parent},
                member(&M::density)),
    };
    return rows;
}

}  // namespace anyphys::schema
