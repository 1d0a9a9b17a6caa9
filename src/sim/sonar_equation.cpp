/// @file sonar_equation.cpp
/// The acoustics layer's closed forms for a simulated head (see sonar_equation.hpp).

#include "sonarmap/sim/sonar_equation.hpp"

#include "sonarmap/acoustics/receiver_model.hpp"
#include "sonarmap/acoustics/sonar_equation.hpp"
#include "sonarmap/sim/acoustic_parameters.hpp"

namespace sonarmap {

double flatSeabedEchoPower(const MsisHeadOptions& head, const EchoModelOptions& echo, double altitude_m,
                           double reflectivity, double range_m, double tilt_rad) {
  head.validate();
  echo.validate();
  return flatSeabedEchoPower(flatSeabedHeadOf(head, echo), FlatSeabed{altitude_m, reflectivity, echo.lambert_exponent},
                             range_m, tilt_rad);
}

double meanNoisePower(const EchoModelOptions& echo, double range_m) {
  echo.validate();
  return meanNoisePower(receiverNoiseOf(echo), range_m);
}

}  // namespace sonarmap
