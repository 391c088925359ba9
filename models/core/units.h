#pragma once
// Units and angle conversions, in one place. Conventions (DESIGN.md): angles are radians in the code
// and degrees at the interfaces (options, parameter files, printed tables); coif's scenes are
// centimetres (right-handed, y up), and assets made in metres (TressFX) are scaled on import.
//
// Each constant is the double nearest the exact value (so kPi == std::numbers::pi and
// kRadiansPerDegree == 0.017453292519943295); the float forms are those doubles rounded once.
#include <concepts>
#include <numbers>

namespace coif {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kTwoPi = 2.0 * kPi;
inline constexpr float kPiF = std::numbers::pi_v<float>;
inline constexpr float kTwoPiF = 2.0f * kPiF;

inline constexpr double kRadiansPerDegree = kPi / 180.0;
inline constexpr double kDegreesPerRadian = 180.0 / kPi;

template <std::floating_point T>
constexpr T radians(T degrees) {
    return degrees * static_cast<T>(kRadiansPerDegree);
}
template <std::floating_point T>
constexpr T degrees(T radians) {
    return radians * static_cast<T>(kDegreesPerRadian);
}

// Scenes are in centimetres; a length in metres times this is in centimetres.
inline constexpr double kCentimetresPerMetre = 100.0;

}  // namespace coif
