// The emulated device, by itself: its replies byte for byte, its motor, its reset, and that
// what it scans decodes to exactly the angles it ray-cast, each sample measured at its own
// moment in the scene, with the scene's dropouts.
#include "drivers/rplidar/rplidar_device_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "drivers/rplidar/rplidar_scan_decoder.h"

namespace slammtt {
namespace rplidar {
namespace {

using Bytes = std::vector<uint8_t>;

Bytes Ask(RplidarDeviceModel& model, const Bytes& request, int64_t now_us) {
  model.OnHostBytes(request.data(), request.size(), now_us);
  return model.TakeOutput(now_us);
}

TEST(RplidarDeviceModelTest, AnswersSingleRequestsByteForByte) {
  RplidarDeviceModel model{RplidarDeviceOptions()};
  EXPECT_EQ(Ask(model, GetHealthRequest(), 0),
            Bytes({0xA5, 0x5A, 0x03, 0x00, 0x00, 0x00, 0x06, 0x00, 0x00, 0x00}));
  EXPECT_EQ(Ask(model, GetSampleRateRequest(), 0),
            Bytes({0xA5, 0x5A, 0x04, 0x00, 0x00, 0x00, 0x15, 0xF4, 0x01, 0xFA, 0x00}));
  EXPECT_EQ(Ask(model, GetAccBoardFlagRequest(), 0),
            Bytes({0xA5, 0x5A, 0x04, 0x00, 0x00, 0x00, 0xFF, 0x00, 0x00, 0x00, 0x00}));
  const Bytes info = Ask(model, GetInfoRequest(), 0);
  ASSERT_EQ(info.size(), 27u);
  EXPECT_EQ(Bytes(info.begin(), info.begin() + 11),
            Bytes({0xA5, 0x5A, 0x14, 0x00, 0x00, 0x00, 0x04, 0x28, 0x1D, 0x01, 0x07}));
  EXPECT_TRUE(Ask(model, EncodeRequest(kGetLidarConf, {0x70, 0, 0, 0}), 0).empty());
  EXPECT_EQ(model.stats().requests.at(kGetInfo), 1);
}

TEST(RplidarDeviceModelTest, ResetReportsABannerAfterBootAndClearsHealth) {
  RplidarDeviceOptions options;
  options.health = {HealthStatus::kError, 0x0101};
  RplidarDeviceModel model(options);
  EXPECT_EQ(Ask(model, GetHealthRequest(), 0).back(), 0x01);
  EXPECT_TRUE(Ask(model, ResetRequest(), 1000).empty());
  // Booting: requests are ignored.
  EXPECT_TRUE(Ask(model, GetHealthRequest(), 2000).empty());
  EXPECT_EQ(model.stats().ignored_requests, 1);
  const Bytes banner = model.TakeOutput(1000 + options.reset_boot_us);
  EXPECT_NE(std::string(banner.begin(), banner.end()).find("Firmware Ver 1.29"), std::string::npos);
  const Bytes health = Ask(model, GetHealthRequest(), 1000 + options.reset_boot_us);
  EXPECT_EQ(health, Bytes({0xA5, 0x5A, 0x03, 0x00, 0x00, 0x00, 0x06, 0x00, 0x00, 0x00}));
}

TEST(RplidarDeviceModelTest, MotorFollowsDtrOrPwm) {
  RplidarDeviceModel dtr_model{RplidarDeviceOptions()};
  dtr_model.SetHostDtr(true, 0);
  EXPECT_FALSE(dtr_model.stats().motor_running);
  dtr_model.SetHostDtr(false, 0);
  EXPECT_TRUE(dtr_model.stats().motor_running);

  RplidarDeviceOptions options;
  options.accessory_board = true;
  RplidarDeviceModel pwm_model(options);
  pwm_model.SetHostDtr(false, 0);
  EXPECT_FALSE(pwm_model.stats().motor_running) << "with the board the motor takes PWM only";
  Ask(pwm_model, SetMotorPwmRequest(660), 0);
  EXPECT_TRUE(pwm_model.stats().motor_running);
  EXPECT_EQ(pwm_model.stats().pwm, 660);
  Ask(pwm_model, SetMotorPwmRequest(0), 0);
  EXPECT_FALSE(pwm_model.stats().motor_running);
}

TEST(RplidarDeviceModelTest, NoScanDataUntilTheMotorIsAtSpeed) {
  RplidarDeviceOptions options;
  RplidarDeviceModel model(options);
  model.SetHostDtr(true, 0);
  EXPECT_EQ(Ask(model, ScanRequest(), 0), EncodeDescriptor(DescriptorFor(kAnswerMeasurement)));
  EXPECT_TRUE(model.TakeOutput(500000).empty());  // motor off
  model.SetHostDtr(false, 500000);
  EXPECT_TRUE(model.TakeOutput(500000 + options.spin_up_us - 1).empty());
  EXPECT_TRUE(model.TakeOutput(500000 + options.spin_up_us).empty());  // the stream starts here
  EXPECT_EQ(model.TakeOutput(500000 + options.spin_up_us + 10 * 500).size(), 50u);  // 10 nodes
}

// Runs a scan in simulated time and decodes it.
std::vector<ScanSample> ScanAndDecode(bool express, int64_t duration_us,
                                      const RplidarDeviceOptions& options) {
  RplidarDeviceModel model(options);
  model.SetHostDtr(false, 0);
  const Bytes descriptor = Ask(model, express ? ExpressScanRequest() : ScanRequest(), 0);
  EXPECT_EQ(descriptor.size(), 7u);
  StandardNodeDecoder standard;
  ExpressCapsuleDecoder capsules;
  std::vector<ScanSample> samples;
  for (int64_t t = 0; t <= duration_us; t += 1000) {
    const Bytes out = model.TakeOutput(t);
    if (express) {
      capsules.Feed(out.data(), out.size(), t, &samples);
    } else {
      standard.Feed(out.data(), out.size(), t, &samples);
    }
  }
  return samples;
}

TEST(RplidarDeviceModelTest, ExpressScanDecodesToTheAnglesThatWereRayCast) {
  RplidarDeviceOptions options;
  options.range_noise_m = 0.0;
  const std::vector<ScanSample> samples = ScanAndDecode(true, 1300000, options);
  // 1 s of data at 4000 samples/s, less the capsule still waiting.
  ASSERT_GE(samples.size(), 3900u);
  int revolutions = 0;
  for (const ScanSample& sample : samples) {
    revolutions += sample.start_of_revolution ? 1 : 0;
    const std::optional<double> range = EmulatedRoom::Default().CastDeviceRay(sample.AngleDeg());
    if (!range) {
      EXPECT_EQ(sample.distance_q2, 0);
      continue;
    }
    // Express distances are whole millimetres; no noise here.
    EXPECT_NEAR(sample.DistanceMm(), *range * 1000.0, 0.51) << sample.AngleDeg();
  }
  EXPECT_GE(revolutions, 9);
}

TEST(RplidarDeviceModelTest, StandardScanMatchesTheRoomWithinNoise) {
  const RplidarDeviceOptions options;
  const std::vector<ScanSample> samples = ScanAndDecode(false, 1300000, options);
  ASSERT_GE(samples.size(), 1900u);
  double sum_squares = 0.0;
  int hits = 0;
  for (const ScanSample& sample : samples) {
    const std::optional<double> range = EmulatedRoom::Default().CastDeviceRay(sample.AngleDeg());
    if (!range) continue;
    const double error_m = sample.DistanceMm() / 1000.0 - *range;
    sum_squares += error_m * error_m;
    ++hits;
  }
  ASSERT_GT(hits, 1500);
  // The noise is the configured 5 mm (Gaussian from hashed uniforms).
  EXPECT_NEAR(std::sqrt(sum_squares / hits), options.range_noise_m, 0.0005);
}

TEST(RplidarDeviceModelTest, SameSeedSameBytesWhateverThePacingWithinTheBacklog) {
  const RplidarDeviceOptions options;
  Bytes fine;
  Bytes coarse;
  for (int pass = 0; pass < 2; ++pass) {
    RplidarDeviceModel model(options);
    model.SetHostDtr(false, 0);
    Ask(model, ExpressScanRequest(), 0);
    Bytes& out = pass == 0 ? fine : coarse;
    // 10 ms = 40 express samples, within the 64-sample backlog the device keeps.
    const int64_t step = pass == 0 ? 1000 : 10000;
    for (int64_t t = step; t <= 400000; t += step) {
      const Bytes chunk = model.TakeOutput(t);
      out.insert(out.end(), chunk.begin(), chunk.end());
    }
  }
  EXPECT_EQ(fine, coarse);
  EXPECT_GT(fine.size(), 84u * 10);
}

}  // namespace
}  // namespace rplidar
}  // namespace slammtt

namespace slammtt {
namespace rplidar {
namespace {

// A scene at 2 m in every direction that remembers the moments it was asked about, with a
// dropout probability of its own.
class RecordingScene : public LaserScene {
 public:
  explicit RecordingScene(double dropout_probability) : dropout_(dropout_probability) {}
  std::optional<SceneReturn> Cast(double, int64_t time_us) const override {
    times_us.push_back(time_us);
    return SceneReturn{2.0, dropout_};
  }
  mutable std::vector<int64_t> times_us;

 private:
  double dropout_;
};

TEST(RplidarDeviceModelTest, EachSampleIsMeasuredAtItsOwnMomentInTheScene) {
  auto scene = std::make_shared<RecordingScene>(0.0);
  RplidarDeviceOptions options;
  options.scene = scene;
  options.range_noise_m = 0.0;
  RplidarDeviceModel model(options);
  model.SetHostDtr(false, 0);
  Ask(model, ScanRequest(), 0);
  // The stream starts once the motor is at speed; node k is measured at epoch + k * 500 us.
  const int64_t epoch = options.spin_up_us;
  model.TakeOutput(epoch);
  const Bytes nodes = model.TakeOutput(epoch + 100 * 500);
  EXPECT_EQ(nodes.size(), 100u * 5u);
  ASSERT_EQ(scene->times_us.size(), 100u);
  for (size_t k = 0; k < scene->times_us.size(); ++k) {
    EXPECT_EQ(scene->times_us[k], epoch + static_cast<int64_t>(k) * 500) << k;
  }
}

TEST(RplidarDeviceModelTest, ASurfacesDropoutProbabilityLosesThatShareOfItsSamples) {
  for (const double probability : {0.0, 0.3, 1.0}) {
    RplidarDeviceOptions options;
    options.scene = std::make_shared<RecordingScene>(probability);
    const std::vector<ScanSample> samples = ScanAndDecode(true, 1300000, options);
    ASSERT_GE(samples.size(), 3900u);
    int lost = 0;
    for (const ScanSample& sample : samples) lost += sample.distance_q2 == 0 ? 1 : 0;
    const double share = static_cast<double>(lost) / static_cast<double>(samples.size());
    // 3900+ draws: a binomial share within 0.03 of p (more than 4 standard deviations).
    EXPECT_NEAR(share, probability, 0.03) << probability;
  }
}

}  // namespace
}  // namespace rplidar
}  // namespace slammtt
