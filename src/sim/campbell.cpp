#include "sim/campbell.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "io/csv_writer.hpp"
#include "io/number_text.hpp"
#include "sim/simulation.hpp"

namespace beltsim {

std::vector<CampbellPoint> campbell(const Scene& sc, const RunSettings& base, const CampbellSettings& s,
                                    const std::atomic<bool>* stop,
                                    const std::function<void(const CampbellPoint&)>& each) {
  if (s.pulley < 0 || s.pulley >= sc.model.n_p()) throw std::invalid_argument("campbell: no such pulley");
  if (!(s.settle > 0 && std::isfinite(s.settle)))
    throw std::invalid_argument("campbell: settle must be a positive time, got " + number_text(s.settle) + " s");
  for (double r : s.rpm)
    if (!(r > 0 && std::isfinite(r)))
      throw std::invalid_argument("campbell: every speed must be positive, got " + number_text(r) + " rpm");
  const int sense = sc.senses()[s.pulley];
  std::vector<CampbellPoint> out;
  for (double r : s.rpm) {
    if (stop && *stop) break;
    Scene at = sc;
    PulleyDrive& p = at.drive.pulleys[s.pulley];
    p.kinematic = true;
    p.torque = TimeSpeedLaw{};
    p.speed = TimeSpeedLaw{};
    p.speed.ramps.push_back(
        {.t0 = 0, .t1 = 0.5 * s.settle, .from = 0, .to = sense * r * 2 * M_PI / 60, .cosine = true});
    RunSettings rs = base;
    rs.t_end = s.settle;
    rs.frames.reset();
    rs.out_dir = (std::filesystem::path(base.out_dir) / ("rpm_" + number_text(r))).string();
    Simulation sim(at, rs);
    sim.run_to(s.settle, stop);
    if (stop && *stop) break;
    CampbellPoint pt{r, analyze_modes(at, sim.drive(), sim.now(), sim.state(), s.modes)};
    sim.close();
    if (each) each(pt);
    out.push_back(std::move(pt));
  }
  return out;
}

void write_campbell_csv(const std::vector<CampbellPoint>& points, const std::string& path) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  f << "rpm,mode,frequency_Hz,damping_ratio,group,share\n";
  for (const CampbellPoint& p : points)
    for (size_t k = 0; k < p.analysis.modes.size(); ++k) {
      const Mode& m = p.analysis.modes[k];
      f << number_text(p.rpm) << ',' << k + 1 << ',' << number_text(m.frequency) << ',' << number_text(m.damping) << ','
        << csv_text(p.analysis.groups[m.dominant]) << ',' << number_text(m.participation[m.dominant]) << '\n';
    }
  f.flush();
  if (!f) throw std::runtime_error("cannot write " + path + ": the disk refused it");
}

}  // namespace beltsim
