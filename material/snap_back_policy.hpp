#pragma once
// What an update does when Eq. (6) has no stable root under the given strain (a snap-back), and
// the policy a user gets without saying: the one place every reader of `snap_back` takes it from
// (material and scene YAML, ecm-point, ecm-mpm, the Python module; docs/model.md, "Snap-back on
// the path"). Code that traces snap-backs itself (ecm-point's driver, the implicit solver's
// attempts) passes Stop explicitly: that is its method, not a default.
#include <optional>
#include <string_view>

namespace ecm {

enum class SnapBackPolicy {
  Stop,     // the update returns UpdateStatus::SnapBack with the state unchanged; ecm-mpm stops the
            // run there, ecm-point stops at the limit point (the driver also uses it to find it)
  Release,  // the band fails at the end strain onto its stable branch
};

inline constexpr SnapBackPolicy kDefaultSnapBack = SnapBackPolicy::Release;

// The YAML and Python spelling: "stop" or "release".
constexpr const char* toString(SnapBackPolicy p) { return p == SnapBackPolicy::Stop ? "stop" : "release"; }
// The policy of a spelling; nullopt for anything else.
constexpr std::optional<SnapBackPolicy> snapBackPolicyOf(std::string_view name) {
  if (name == "stop") return SnapBackPolicy::Stop;
  if (name == "release") return SnapBackPolicy::Release;
  return std::nullopt;
}

}  // namespace ecm
