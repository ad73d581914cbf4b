// PRISM_WIRE_FIELDS lists a struct's fields once, in declaration order, as a static member
// fields(self, visit); wire/Fields.h says what follows from the list (encoding, decoding,
// equality). It lives here, below every layer, so that a struct of any layer (a primitive's
// description in geometry/, a photon in caustics/) can list its own fields without knowing the
// wire.
#pragma once

#define PRISM_WIRE_FIELDS(...)                   \
  static void fields(auto& self, auto&& visit) { \
    auto& [__VA_ARGS__] = self;                  \
    visit(__VA_ARGS__);                          \
  }
