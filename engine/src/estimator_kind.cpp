// The names of the estimators, as the command line and the reports spell them.
#include <string>

#include "gridloc/engine/estimator.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc {

std::string to_string(EstimatorKind kind) {
  switch (kind) {
    case EstimatorKind::Correlation:
      return "correlation";
    case EstimatorKind::Icp:
      return "icp";
    case EstimatorKind::CorrelationIcp:
      return "correlation+icp";
    case EstimatorKind::Sectors:
      return "sectors";
    case EstimatorKind::SectorsCorrelation:
      return "sectors+correlation";
  }
  return "?";
}

bool is_sector_estimator(EstimatorKind kind) {
  return kind == EstimatorKind::Sectors || kind == EstimatorKind::SectorsCorrelation;
}

EstimatorKind parse_estimator_kind(const std::string& name) {
  for (EstimatorKind k :
       {EstimatorKind::Correlation, EstimatorKind::Icp, EstimatorKind::CorrelationIcp,
        EstimatorKind::Sectors, EstimatorKind::SectorsCorrelation}) {
    if (to_string(k) == name) return k;
  }
  throw Error(
      "the estimator must be correlation, icp, correlation+icp, sectors or sectors+correlation, "
      "not '" +
      name + "'");
}

}  // namespace gridloc
