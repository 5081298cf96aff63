// The one definition of pi in the core (a constant defined in two .cpp files
// would clash when a unity build compiles them together).
#pragma once

namespace aniso {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegToRad = kPi / 180.0;

}  // namespace aniso
