#include "estimator/manoeuvres.h"

#include "estimator/ekf_prediction.h"

namespace slammtt {
namespace {

// Whether the jump is what lets level 3 take a free measurement: one lies inside `gate` of
// `prediction` widened by a position jump of jump_m standard deviation, and none lies inside
// `gate` of the prediction as it is (level 3 takes that one without a jump).
bool JumpLetsLevel3TakeAMeasurement(const ObjectPrediction& prediction, double jump_m,
                                    const ScanAssociation& scan, double gate,
                                    const Assignment& assignment) {
  ObjectPrediction widened = prediction;
  widened.hph += jump_m * jump_m * prediction.jacobian_position *
                 prediction.jacobian_position.transpose();
  bool inside_widened = false;
  for (int i = 0; i < assignment.num_measurements(); ++i) {
    if (!assignment.MeasurementFree(i)) continue;
    const PointMeasurement& z = scan.measurements[static_cast<size_t>(i)];
    if (NormalizedInnovationSquared(z, prediction, gate) < gate) return false;
    inside_widened = inside_widened || NormalizedInnovationSquared(z, widened, gate) < gate;
  }
  return inside_widened;
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
    if (JumpLetsLevel3TakeAMeasurement(p, jump_m, scan, options.gate_d2_chi2, assignment)) {
      AddVelocityJump(j, dt_s, sigma, state);
      ++counts->manoeuvres;
    }
  }
}

}  // namespace slammtt
