// Data described once: every struct that crosses the wire lists its fields in one function, in
// wire order, and encoding, decoding and field-wise equality (wire/FieldCodec.h) follow from that
// list. A struct of the wire's own lists them as a static member; one that a lower layer owns
// (scene/, render/, caustics/: they know nothing of the wire) gets a specialisation of Fields
// here in the wire:
//
//   struct ProgressMessage {
//     uint32_t frame = 0;
//     uint64_t jobsReceived = 0;
//     std::vector<uint32_t> heldTiles;
//     PRISM_WIRE_FIELDS(frame, jobsReceived, heldTiles)
//   };
//   template <> struct Fields<TileRect> {
//     PRISM_WIRE_FIELDS(x, y, width, height)
//     static void check(const TileRect& rect);  // optional: run once the fields are read
//   };
//
// PRISM_WIRE_FIELDS names every member in declaration order through a structured binding, so a
// member added to the struct breaks the build until the list names it: a new field cannot stay
// behind. Where the wire order differs from the declaration order, or a field needs a wrapper,
// the list is written out, still through a binding:
//
//   static void fields(auto& self, auto&& visit) {
//     auto& [center, radius, material, loc, caustic] = self;
//     visit(center, radius, material, caustic, loc);
//   }
//
// self is const when encoding or comparing and not when decoding: one list serves all three.
//
// What a field may be: an integer of fixed width, float, double, bool, std::string, Vec3, an
// enumeration (a u32 on the wire, refused unless it names an enumerator: wire/WireEnums.h), a
// described struct, std::optional, std::array, a C array, or std::vector of any of these (a u64
// count first; a vector of values whose memory is their wire form is copied in one go); or one
// of the wrappers below. A count is checked against the bytes left before anything is allocated.
#pragma once

#include <concepts>
#include <cstddef>
#include <type_traits>

#include "util/FieldList.h"

namespace prism::wire {

// Specialised for the structs of other layers that travel: fields(self, visit) as above, and
// optionally check(const T&) and kMemoryIsWireForm (see FieldCodec.h).
template <class T>
struct Fields {};

// A bool whose bad byte the error names ("invalid jitter flag 3" rather than "invalid bool").
template <class B>
struct Flag {
  B& value;
  const char* what;
};
template <class B>
Flag<B> flag(B& value, const char* what) {
  return {value, what};
}

// A vector whose elements are checked as they are read: check(element, index) throws WireError.
// Values copied in one go are checked a block at a time, while the block is still in the cache.
template <class Vector, class Check>
struct Each {
  Vector& values;
  Check check;
};
template <class Vector, class Check>
Each<Vector, Check> each(Vector& values, Check check) {
  return {values, check};
}

// A field with a wire form of its own (one whose form depends on another field) is a type with
// write(ByteWriter&) const and read(ByteReader&); two are equal when they write the same bytes.
// It may list what it carries too, for tools that walk the fields.
template <class T>
concept CustomField = requires(const T& t) {
  &T::write;
};

struct IgnoreFields {
  void operator()(auto&&...) const {}
};

template <class T>
concept OwnFields = requires(T& t, IgnoreFields v) {
  T::fields(t, v);
};
template <class T>
concept ForeignFields = requires(T& t, IgnoreFields v) {
  Fields<T>::fields(t, v);
};
template <class T>
concept Described = OwnFields<T> || ForeignFields<T>;

// Calls visit with every field of self (const or not), in wire order.
template <class Self, class Visit>
void visitFields(Self& self, Visit&& visit) {
  using T = std::remove_const_t<Self>;
  if constexpr (OwnFields<T>) {
    T::fields(self, visit);
  } else {
    Fields<T>::fields(self, visit);
  }
}

// The struct's own check, if it has one: what no single field can say (ranges that depend on
// each other, counts that must agree). Throws WireError.
template <class T>
void checkFields(const T& value) {
  if constexpr (requires { T::check(value); }) {
    T::check(value);
  } else if constexpr (requires { Fields<T>::check(value); }) {
    Fields<T>::check(value);
  }
}

}  // namespace prism::wire
