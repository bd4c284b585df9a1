// LogSummary LOG.lcm: reads an LCM event log with LCM's own Java reader (lcm.logging.Log) and
// decodes every LASER_SCAN, ODOMETRY and GROUND_TRUTH event with the generated classes of
// slammtt_msgs.jar. Prints one line per channel:
//   CHANNEL EVENTS FIRST_UTIME LAST_UTIME SUM
// where the utimes are the decoded messages' own and SUM adds one field over every event in log
// order (LASER_SCAN: range_m of the valid beams; ODOMETRY: x_m; GROUND_TRUTH: robot_x_m), written
// by Double.toString, the shortest text that reads back as the same double. A message that does
// not decode (wrong fingerprint, truncated) ends the program with its exception. The test
// java_types_test compares these lines with what the C++ decoder reads from the same log.
import java.io.EOFException;
import java.io.IOException;
import java.util.LinkedHashMap;
import java.util.Map;
import lcm.logging.Log;
import slammtt_msgs.ground_truth_t;
import slammtt_msgs.laser_scan_t;
import slammtt_msgs.odometry_t;

public final class LogSummary {
  private static final class ChannelSummary {
    long events;
    long firstUtime;
    long lastUtime;
    double sum;

    void add(long utime, double value) {
      if (events == 0) firstUtime = utime;
      lastUtime = utime;
      events++;
      sum += value;
    }
  }

  public static void main(String[] args) throws IOException {
    if (args.length != 1) {
      System.err.println("usage: LogSummary LOG.lcm");
      System.exit(2);
    }
    Map<String, ChannelSummary> channels = new LinkedHashMap<>();
    for (String channel : new String[] {"LASER_SCAN", "ODOMETRY", "GROUND_TRUTH"}) {
      channels.put(channel, new ChannelSummary());
    }
    Log log = new Log(args[0], "r");
    while (true) {
      Log.Event event;
      try {
        event = log.readNext();
      } catch (EOFException end) {
        break;
      }
      ChannelSummary summary = channels.get(event.channel);
      if (summary == null) continue;
      switch (event.channel) {
        case "LASER_SCAN": {
          laser_scan_t scan = new laser_scan_t(event.data);
          double valid_ranges_m = 0;
          for (int i = 0; i < scan.num_beams; i++) {
            if (scan.valid[i]) valid_ranges_m += scan.range_m[i];
          }
          summary.add(scan.utime, valid_ranges_m);
          break;
        }
        case "ODOMETRY": {
          odometry_t odometry = new odometry_t(event.data);
          summary.add(odometry.utime, odometry.x_m);
          break;
        }
        default: {
          ground_truth_t truth = new ground_truth_t(event.data);
          summary.add(truth.utime, truth.robot_x_m);
          break;
        }
      }
    }
    log.close();
    for (Map.Entry<String, ChannelSummary> entry : channels.entrySet()) {
      ChannelSummary s = entry.getValue();
      System.out.println(entry.getKey() + " " + s.events + " " + s.firstUtime + " " + s.lastUtime
                         + " " + Double.toString(s.sum));
    }
  }
}
