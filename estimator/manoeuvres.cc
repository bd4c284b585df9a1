#include "estimator/manoeuvres.h"

#include "estimator/ekf_prediction.h"

namespace slammtt {
namespace {

// Whether a free measurement lies inside gate dn of `prediction` widened by a position jump of
// jump_m standard deviation.
bool FreeMeasurementInWidenedGate(const ObjectPrediction& prediction, double jump_m,
                                  const ScanAssociation& scan, double gate_dn,
                                  const Assignment& assignment) {
  ObjectPrediction widened = prediction;
  widened.hph += jump_m * jump_m * prediction.jacobian_position *
                 prediction.jacobian_position.transpose();
  for (int i = 0; i < assignment.num_measurements(); ++i) {
    if (!assignment.MeasurementFree(i)) continue;
    if (NormalizedInnovationSquared(scan.measurements[static_cast<size_t>(i)], widened,
                                    gate_dn) < gate_dn) {
      return true;
    }
  }
  return false;
}

}  // namespace

void GiveManoeuvringMoversAVelocityJump(double dt_s, const ScanAssociation& scan,
                                        const EstimatorOptions& options,
                                        ObservationPredictions* predicted, SlamState* state,
                                        const Assignment& assignment, StepCounts* counts) {
  const double sigma = options.manoeuvre_velocity_sigma_mps;
  if (!(sigma > 0.0 && dt_s > 0.0)) return;
  const double jump_m = sigma * dt_s;
  // A jump changes only its own object's blocks, so the predictions of the others stay those
  // of the state before it.
  const std::vector<ObjectPrediction>& now = predicted->At(*state);
  for (int j = 0; j < assignment.num_objects(); ++j) {
    const StateObject& object = state->object(j);
    const ObjectPrediction& p = now[static_cast<size_t>(j)];
    if (!assignment.ObjectFree(j) || !object.has_velocity() || !p.valid ||
        object.record.object_class != ObjectClass::kMoving) {
      continue;
    }
    if (FreeMeasurementInWidenedGate(p, jump_m, scan, options.new_object_gate_dn_chi2,
                                     assignment)) {
      AddVelocityJump(j, dt_s, sigma, state);
      ++counts->manoeuvres;
    }
  }
}

}  // namespace slammtt
