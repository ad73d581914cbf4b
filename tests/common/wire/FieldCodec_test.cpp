// The generic codec, over every message type of PRISM_WIRE_MESSAGES: a new type is covered
// without a line here. Examples come from the field lists (tests/fuzz/WireExamples.h).
#include "wire/FieldCodec.h"

#include <gtest/gtest.h>

#include <random>
#include <set>
#include <string>

#include "fuzz/WireExamples.h"
#include "wire/GeometryCodec.h"
#include "wire/Messages.h"

namespace prism::wire {
namespace {

template <class T>
const char* nameOf() {
  return messageTypeName(MessageTraits<T>::kType);
}

// Decodes payload as a T message; "" if accepted and encoding back to the same bytes, else the
// WireError's text. Any other exception fails the test.
template <class T>
std::string outcome(const std::vector<uint8_t>& payload) {
  const std::vector<uint8_t> bytes = encodeMessage(MessageTraits<T>::kType, payload);
  try {
    const T decoded = decode<T>(decodeMessage(bytes));
    EXPECT_EQ(encode(decoded), bytes) << nameOf<T>() << ": accepted but encodes differently";
    return "";
  } catch (const WireError& e) {
    return e.what();
  }
}

template <class T>
std::vector<uint8_t> payloadOf(const T& value) {
  return decodeMessage(encode(value)).payload;
}

template <class T>
std::vector<T> acceptedValues() {
  std::vector<T> values;
  T candidates[] = {T{}, fuzz::filledExample<T>()};  // moved, not copied: a geometry has no copy
  for (T& value : candidates) {
    if (outcome<T>(payloadOf(value)).empty()) values.push_back(std::move(value));
  }
  return values;
}

TEST(FieldCodec, TheTypeListGivesEachTypeItsNumberNameAndStruct) {
  std::set<std::string> names;
  std::set<int> numbers;
  forEachMessageType([&](auto type) {
    using T = typename decltype(type)::type;
    const MessageType t = MessageTraits<T>::kType;
    EXPECT_TRUE(isKnownType(static_cast<uint16_t>(t)));
    EXPECT_TRUE(names.insert(messageTypeName(t)).second) << messageTypeName(t);
    EXPECT_TRUE(numbers.insert(static_cast<int>(t)).second) << messageTypeName(t);
    // The dispatch decodes a message of this type as this struct.
    const std::vector<uint8_t> bytes = fuzz::acceptedExamples<T>().at(0).bytes;
    visitMessage(decodeMessage(bytes), [&](const auto& decoded) {
      EXPECT_TRUE((std::is_same_v<std::decay_t<decltype(decoded)>, T>)) << messageTypeName(t);
    });
  });
  EXPECT_EQ(names.size(), numbers.size());
  EXPECT_EQ(*numbers.rbegin() + 1, firstUnusedTypeNumber());
  // Known are exactly the list's numbers.
  for (int raw = 0; raw <= firstUnusedTypeNumber(); ++raw) {
    EXPECT_EQ(isKnownType(static_cast<uint16_t>(raw)), numbers.count(raw) == 1) << raw;
  }
  EXPECT_FALSE(isKnownType(0xFFFF));
}

TEST(FieldCodec, EveryMessageTypeRoundTripsFieldForField) {
  forEachMessageType([](auto type) {
    using T = typename decltype(type)::type;
    const std::vector<T> values = acceptedValues<T>();
    EXPECT_FALSE(values.empty()) << nameOf<T>() << ": neither example is accepted";
    for (const T& value : values) {
      const std::vector<uint8_t> bytes = encode(value);
      const T back = decode<T>(decodeMessage(bytes));
      EXPECT_TRUE(sameFields(back, value)) << nameOf<T>();
      EXPECT_EQ(encode(back), bytes) << nameOf<T>();
    }
  });
  // sameFields compares every field, floats by bit pattern.
  ReadyMessage a{0.5, 2}, b = a;
  EXPECT_TRUE(sameFields(a, b));
  b.mpiInitSeconds = -0.0;
  EXPECT_FALSE(sameFields(a, b));
  SceneDescription s = fuzz::filledExample<SceneDescription>(), t = s;
  EXPECT_TRUE(sameFields(s, t));
  t.meshes[0].loc.column = 2;
  EXPECT_FALSE(sameFields(s, t));
}

TEST(FieldCodec, EveryTruncationOfEveryMessageTypeIsRejected) {
  forEachMessageType([](auto type) {
    using T = typename decltype(type)::type;
    for (const T& value : acceptedValues<T>()) {
      const std::vector<uint8_t> payload = payloadOf(value);
      for (size_t length = 0; length < payload.size(); ++length) {
        const std::vector<uint8_t> prefix(payload.begin(), payload.begin() + length);
        EXPECT_NE(outcome<T>(prefix), "") << nameOf<T>() << " cut to " << length << " bytes";
      }
      // The envelope's own size check, whatever the type.
      const std::vector<uint8_t> bytes = encode(value);
      EXPECT_THROW(decodeMessage(bytes.data(), bytes.size() - 1), WireError) << nameOf<T>();
    }
  });
}

TEST(FieldCodec, EveryMessageTypeRefusesBytesLeftOverAndALargerDeclaredSize) {
  forEachMessageType([](auto type) {
    using T = typename decltype(type)::type;
    for (const T& value : acceptedValues<T>()) {
      std::vector<uint8_t> payload = payloadOf(value);
      payload.push_back(0);
      EXPECT_NE(outcome<T>(payload).find("unexpected trailing data"), std::string::npos)
          << nameOf<T>();
      std::vector<uint8_t> bytes = encode(value);
      bytes[8] += 1;  // the declared payload size (u64 at offset 8)
      EXPECT_THROW(decodeMessage(bytes), WireError) << nameOf<T>();
    }
  });
}

// 0xFF bytes, longer than the valid payload: every count and length reads huge, every enumerator
// unknown, and a type without either is left with bytes over. Refused, and before anything huge
// is allocated (that would throw std::bad_alloc or std::length_error, not WireError).
TEST(FieldCodec, EveryMessageTypeRefusesGarbage) {
  forEachMessageType([](auto type) {
    using T = typename decltype(type)::type;
    for (const T& value : acceptedValues<T>()) {
      const std::vector<uint8_t> garbage(payloadOf(value).size() + 8, 0xFF);
      EXPECT_NE(outcome<T>(garbage), "") << nameOf<T>();
    }
  });
}

// A count or length anywhere replaced by a huge one: refused with WireError (or, where the bytes
// were not a length, accepted as a value that encodes back the same), never a huge allocation.
TEST(FieldCodec, AHugeLengthAnywhereInAnyMessageIsRefusedWithoutAllocating) {
  forEachMessageType([](auto type) {
    using T = typename decltype(type)::type;
    const std::vector<uint8_t> payload = payloadOf(fuzz::filledExample<T>());
    int countsRefused = 0;
    for (size_t at = 0; at + 4 <= payload.size(); ++at) {
      for (const uint64_t huge : {uint64_t{1} << 60, uint64_t{0xFFFFFFF0}}) {
        std::vector<uint8_t> bad = payload;
        for (size_t i = 0; i < 8 && at + i < bad.size(); ++i) bad[at + i] = uint8_t(huge >> 8 * i);
        const std::string error = outcome<T>(bad);
        if (error.find("corrupt element count") != std::string::npos ||
            error.find("truncated message: needed") != std::string::npos) {
          ++countsRefused;
        }
      }
    }
    // A type whose filled example (one element in each vector, one character in each string) is
    // longer than its default carries counts or lengths, and some of them were hit.
    if (payload.size() != payloadOf(T{}).size()) {
      EXPECT_GT(countsRefused, 0) << nameOf<T>();
    }
  });
}

TEST(FieldCodec, RandomPayloadsAreRefusedOrDecodeToThemselves) {
  std::mt19937 random(50);
  forEachMessageType([&](auto type) {
    using T = typename decltype(type)::type;
    for (int attempt = 0; attempt < 200; ++attempt) {
      std::vector<uint8_t> payload(random() % 96);
      for (uint8_t& byte : payload) byte = static_cast<uint8_t>(random() % 4 == 0 ? random() : 0);
      outcome<T>(payload);  // fails the test on anything but WireError or the same bytes
    }
  });
}

TEST(FieldCodec, EveryDecoderRefusesEveryOtherType) {
  forEachMessageType([](auto type) {
    using T = typename decltype(type)::type;
    const Message message = decodeMessage(fuzz::acceptedExamples<T>().at(0).bytes);
    forEachMessageType([&](auto other) {
      using U = typename decltype(other)::type;
      if constexpr (!std::is_same_v<T, U>) {
        try {
          decode<U>(message);
          ADD_FAILURE() << nameOf<U>() << " decoded a " << nameOf<T>();
        } catch (const WireError& e) {
          EXPECT_EQ(std::string(e.what()),
                    std::string("expected a ") + nameOf<U>() + " message, got " + nameOf<T>());
        }
      }
    });
  });
}

// The photon map's overload that does not copy the photons reads the same field list.
TEST(FieldCodec, PhotonMapWithoutACopyIsTheSameBytes) {
  PhotonMapMessage map = fuzz::filledExample<PhotonMapMessage>();
  map.photons.resize(3, map.photons[0]);
  map.photons[2].position.y = -7.0f;
  for (const bool keep : {false, true}) {
    map.keep = keep;
    EXPECT_EQ(encodePhotonMap(map.pass, map.gather, map.photons, map.keep), encode(map));
  }
}

}  // namespace
}  // namespace prism::wire
