#include "cluster/FaultInjection.h"

#include <iterator>
#include <stdexcept>
#include <utility>

namespace prism {
namespace {

// Each kind's name on the command line, in the order the error lists them.
constexpr std::pair<const char*, FaultInjection::Kind> kKindNames[] = {
    {"hang", FaultInjection::Kind::Hang},   {"drop", FaultInjection::Kind::DropTiles},
    {"crash", FaultInjection::Kind::Crash}, {"crash-photons", FaultInjection::Kind::CrashOnPhotons},
    {"slow", FaultInjection::Kind::Slow},
};

FaultInjection::Kind kindNamed(const std::string& name) {
  for (const auto& [text, kind] : kKindNames) {
    if (name == text) return kind;
  }
  return FaultInjection::Kind::None;
}

// The rank after the colon; -1 unless the rest is a whole decimal number.
int rankAfter(const std::string& text, size_t colon) {
  if (colon == std::string::npos) return -1;
  size_t used = 0;
  try {
    const int rank = std::stoi(text.substr(colon + 1), &used);
    return used == text.size() - colon - 1 ? rank : -1;
  } catch (const std::exception&) {
    return -1;
  }
}

}  // namespace

std::string faultInjectionForms() {
  std::string forms;
  for (size_t i = 0; i < std::size(kKindNames); ++i) {
    if (i > 0) forms += i + 1 == std::size(kKindNames) ? " or " : ", ";
    forms += std::string(kKindNames[i].first) + ":RANK";
  }
  return forms;
}

FaultInjection parseFaultInjection(const std::string& text) {
  const size_t colon = text.find(':');
  FaultInjection fault;
  fault.kind = kindNamed(text.substr(0, colon));
  fault.rank = rankAfter(text, colon);
  if (fault.kind == FaultInjection::Kind::None || fault.rank < 1) {
    throw std::invalid_argument("fault injection '" + text + "' must be " + faultInjectionForms() +
                                " with a slave rank >= 1");
  }
  return fault;
}

}  // namespace prism
