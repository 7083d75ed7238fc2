#pragma once
// What the Bullet backend tests share.
#include "anyphys/anyphys.hpp"

namespace anyphys::bullet::test {

inline WorldSettings bulletSettings() {
    WorldSettings s;
    s.backend = "bullet";
    return s;
}

}  // namespace anyphys::bullet::test
