// Driver files and series (core/vehicle/driver_inputs.hpp): the LFDM/Chrono files read as they are,
// values are linear between rows and held outside them, and every bad file is refused with a
// message that names FILE:LINE, the column and the value.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "../../scratch_dir.hpp"
#include "../reader_cases.hpp"
#include "core/errors.hpp"
#include "core/vehicle/driver_inputs.hpp"

using namespace std::string_literals;
using terracal::DriverInput;
using terracal::DriverSeries;
using terracal::InputError;
using terracal::test::ReaderCase;
using terracal::test::write_bytes;

namespace {

// uwsbel/low-fidelity-dynamic-models, wheeled_vehicle_models/18dof/data/input/st6_right.txt, byte for
// byte: tabs in the first rows, runs of spaces and a trailing space later.
const std::string kLfdmFile =
    "0\t 0\t0\t0\n"
    "1\t 0\t0\t0\n"
    "4.5\t 0\t0.6\t0\n"
    "8.5      0      0.6     0\n"
    "10       0      0.8     0 \n"
    "14       0      0.2     0\n"
    "17       -0.5   0       0\n"
    "17.5     0      0       0\n"
    "18       0      0.2     0\n"
    "20       0      0       0\n";

void check_input(const DriverInput& in, double steering, double throttle, double braking) {
  CHECK(in.steering == Approx(steering).margin(1e-12));
  CHECK(in.throttle == Approx(throttle).margin(1e-12));
  CHECK(in.braking == Approx(braking).margin(1e-12));
}

}  // namespace

TEST_CASE("driver file: an LFDM file reads as it is, linear between rows and held outside them", "[driver_inputs]") {
  const terracal::test::ScratchDir scratch("driver_lfdm");
  const std::string path = scratch.str() + "/st6_right.txt";
  write_bytes(path, kLfdmFile);
  const DriverSeries s = DriverSeries::read(path);
  REQUIRE(s.size() == 10);
  CHECK(s.source() == path);
  CHECK(s.start_time() == 0);
  CHECK(s.end_time() == 20);
  CHECK(s.times()[3] == 8.5);
  CHECK(s.throttle()[4] == 0.8);
  CHECK(s.steering()[6] == -0.5);

  check_input(s.at(4.5), 0, 0.6, 0);                    // on a row
  check_input(s.at(2.75), 0, 0.3, 0);                   // halfway between 1 (0) and 4.5 (0.6)
  check_input(s.at(9.25), 0, 0.7, 0);                   // halfway between 8.5 (0.6) and 10 (0.8)
  check_input(s.at(11), 0, 0.65, 0);                    // a quarter from 10 (0.8) to 14 (0.2)
  check_input(s.at(16.5), -0.5 * 2.5 / 3, 0.2 / 6, 0);  // 14 -> 17: steering 0 -> -0.5, throttle 0.2 -> 0
  check_input(s.at(17.25), -0.25, 0, 0);                // back to straight by 17.5
  check_input(s.at(-5), 0, 0, 0);                       // before the first row: the first row
  check_input(s.at(1e6), 0, 0, 0);                      // after the last row: the last row
  check_input(s.at(std::nan("")), 0, 0, 0);

  // The device view reads the same values as the series.
  const terracal::DriverSeriesView v = s.view();
  REQUIRE(v.n == 10);
  for (double t = -1; t < 22; t += 0.37) {
    const DriverInput a = s.at(t), b = v.at(t);
    CHECK(a.steering == b.steering);
    CHECK(a.throttle == b.throttle);
    CHECK(a.braking == b.braking);
  }
}

TEST_CASE("driver file: commas, mixed separators, comments, blank lines, CRLF and a BOM", "[driver_inputs]") {
  const terracal::test::ScratchDir scratch("driver_mixed");
  const std::string path = scratch.str() + "/driver.txt";
  write_bytes(path,
              "\xEF\xBB\xBF# time, steering, throttle, braking\r\n"
              "\r\n"
              "-1,0,0,0\r\n"
              "   # an indented comment\n"
              "  1 , 0.5 ,0.2, 0\n"
              "3\t-0.5, +1 ,0\n"
              "\n"
              "4 -1 0 1e-1\n");
  const DriverSeries s = DriverSeries::read(path);
  REQUIRE(s.size() == 4);
  CHECK(s.start_time() == -1);  // a negative start time is fine
  check_input(s.at(0), 0.25, 0.1, 0);
  check_input(s.at(2), 0, 0.6, 0);
  check_input(s.at(3.5), -0.75, 0.5, 0.05);
  check_input(s.at(4), -1, 0, 0.1);
}

TEST_CASE("driver file: the lookup finds the right interval in a long series", "[driver_inputs]") {
  std::vector<double> t, st, th, br;
  for (int i = 0; i < 5001; ++i) {
    t.push_back(0.01 * i + 1e-4 * i * i / 5000.0);  // uneven steps
    st.push_back(std::sin(0.01 * i));
    th.push_back(0.5 + 0.5 * std::cos(0.003 * i));
    br.push_back(i % 2 ? 0.25 : 0.0);
  }
  const DriverSeries s = DriverSeries::from_rows(t, st, th, br, "sine rows");
  for (int i = 0; i < 5000; i += 37) {
    const double w = 0.3, at = t[i] + w * (t[i + 1] - t[i]);
    check_input(s.at(at), st[i] + w * (st[i + 1] - st[i]), th[i] + w * (th[i + 1] - th[i]),
                br[i] + w * (br[i + 1] - br[i]));
    check_input(s.at(t[i]), st[i], th[i], br[i]);
  }
}

TEST_CASE("driver series: the lookup from a cursor gives the bisection's value to the bit", "[driver_inputs]") {
  std::vector<double> t, st, th, br;
  for (int i = 0; i < 400; ++i) {
    t.push_back(0.05 * i + 1e-3 * std::sin(double(i)));  // uneven steps
    st.push_back(std::sin(0.1 * i));
    th.push_back(0.5 + 0.5 * std::cos(0.03 * i));
    br.push_back(i % 3 ? 0.25 : 0.0);
  }
  const DriverSeries s = DriverSeries::from_rows(t, st, th, br, "uneven rows");
  const terracal::DriverSeriesView v = s.view();
  auto same = [](const DriverInput& a, const DriverInput& b) {
    return a.steering == b.steering && a.throttle == b.throttle && a.braking == b.braking;
  };
  // A run's steps: before the first row, on rows, between them, past the last; steps shorter and
  // longer than the rows' spacing.
  for (double h : {1e-3, 0.013, 0.05, 0.31}) {
    int cursor = 0;
    long mismatches = 0;
    for (double at = -0.2; at < t.back() + 0.5; at += h) mismatches += !same(v.at(at, cursor), v.at(at));
    for (int i = 0; i < 400; ++i) mismatches += !same(v.at(t[i], cursor), v.at(t[i]));
    CHECK(mismatches == 0);
  }
  // Times that go back, and a cursor that points anywhere, still give the bisection's value.
  int cursor = 350;
  CHECK(same(v.at(1.234, cursor), v.at(1.234)));
  CHECK(cursor == 24);
  for (int bad : {-5, 399, 400, 100000}) {
    cursor = bad;
    CHECK(same(v.at(7.77, cursor), v.at(7.77)));
  }
}

TEST_CASE("driver file: bad files are refused, naming the file, the line, the column and the value",
          "[driver_inputs]") {
  const terracal::test::ScratchDir scratch("driver_bad");
  const std::string path = scratch.str() + "/driver.txt";
  const std::vector<ReaderCase> cases = {
      {"text in a number", "0 0 0 0\n1 abc 0 0\n", ":2: column \"steering\" value \"abc\"", {"expected a number"}},
      {"a header row",
       "time steering throttle braking\n0 0 0 0\n",
       ":1: column \"time\" value \"time\"",
       {"header row"}},
      {"three columns", "0 0 0 0\n# note\n1 0 0\n", ":3: found 3 values", {"'1 0 0'", "expected 4"}},
      {"five columns", "0,0,0,0,0\n", ":1: found 5 values", {"expected 4: time steering throttle braking"}},
      {"an empty value", "0,,0,0,0\n", ":1: an empty value before a comma", {"'0,,0,0,0'"}},
      {"a trailing comma", "0,0,0,0,\n", ":1: the row '0,0,0,0,' ends with a comma", {}},
      {"NaN", "0 nan 0 0\n", ":1: column \"steering\" value \"nan\": expected a finite number", {}},
      {"infinity", "0 0 0 0\ninf 0 0 0\n", ":2: column \"time\" value \"inf\": expected a finite number", {}},
      {"1e309", "0 0 1e309 0\n", ":1: column \"throttle\": '1e309' is out of range for a double", {}},
      {"a repeated time",
       "0 0 0 0\n# same again\n0 0 0.1 0\n",
       ":3: column \"time\" value \"0\": expected a time greater than 0 (the time on line 1)",
       {"increase strictly"}},
      {"a decreasing time",
       "0 0 0 0\n2 0 0 0\n1.5 0 0 0\n",
       ":3: column \"time\" value \"1.5\": expected a time greater than 2 (the time on line 2)",
       {}},
      {"steering above 1", "0 1.5 0 0\n", ":1: column \"steering\" value \"1.5\": expected a number in [-1, 1]", {}},
      {"steering below -1",
       "0 -1.01 0 0\n",
       ":1: column \"steering\" value \"-1.01\": expected a number in [-1, 1]",
       {}},
      {"throttle above 1",
       "0 0 0 0\n1 0 1.5 0\n",
       ":2: column \"throttle\" value \"1.5\": expected a number in [0, 1]",
       {}},
      {"negative throttle", "0 0 -0.1 0\n", ":1: column \"throttle\" value \"-0.1\": expected a number in [0, 1]", {}},
      {"braking above 1", "0 0 0 2\n", ":1: column \"braking\" value \"2\": expected a number in [0, 1]", {}},
      {"an empty file", "", ": the driver file has no rows", {"time steering throttle braking"}},
      {"only comments", "# nothing here\n\n   \n", ": the driver file has no rows", {}},
      {"Latin-1", "0 0 0 0\n# caf\xE9\n", ":2:6: found bytes E9", {"expected UTF-8 text"}},
      {"a 40000-character token",
       "0 0 0 " + std::string(40000, '9') + "x\n",
       ":1: column \"braking\" value \"9999",
       {"(40001 characters)", "expected a number"}},
  };
  terracal::test::check_refusals(cases, path, [](const std::string& p) { DriverSeries::read(p); });
}

TEST_CASE("driver file: a missing file is refused naming it", "[driver_inputs]") {
  const std::string path = "/nonexistent/terracal/driver.txt";
  const std::string message = terracal::test::input_error_of([](const std::string& p) { DriverSeries::read(p); }, path);
  INFO(message);
  CHECK(message.find(path) != std::string::npos);
}

TEST_CASE("driver rows: rows built in code pass the same checks, naming the row", "[driver_inputs]") {
  const auto message = [](std::vector<double> t, std::vector<double> s, std::vector<double> th, std::vector<double> b) {
    try {
      DriverSeries::from_rows(t, s, th, b, "test rows");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK(message({0, 1}, {0, 0}, {0, 1.5}, {0, 0}) ==
        "test rows: row 2: column \"throttle\" value \"1.5\": expected a number in [0, 1]");
  CHECK(message({0, 1, 1}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0})
            .find("test rows: row 3: column \"time\" value \"1\": "
                  "expected a time greater than 1 (the time on row 2)") == 0);
  CHECK(message({0, 1}, {0}, {0, 0}, {0, 0}).find("test rows: the columns have different lengths") == 0);
  CHECK(message({}, {}, {}, {}).find("test rows: no rows") == 0);
  CHECK(message({0}, {-2}, {0}, {0}).find("row 1: column \"steering\" value \"-2\"") != std::string::npos);
  CHECK(message({0, 1}, {0, 0}, {0, 0}, {0, 0}).empty());
  // A single row holds for all times.
  const DriverSeries one = DriverSeries::from_rows({2}, {0.5}, {0.25}, {0}, "one row");
  check_input(one.at(-10), 0.5, 0.25, 0);
  check_input(one.at(10), 0.5, 0.25, 0);
  CHECK(one.end_time() == 2);
}
