// An object's part in caustics. Auto: casts when its material reflects or transmits
// specularly, receives when it has a diffuse albedo. Cast/Receive restrict it to one role,
// Both forces both, Off takes it out of caustics entirely (photons that reach it are absorbed).
#pragma once

#include <cstdint>

namespace prism {

enum class CausticRole : uint8_t { Auto, Cast, Receive, Both, Off };

}  // namespace prism
