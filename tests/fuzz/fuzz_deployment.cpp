// Deployment descriptions (deploy/hosts/*.yaml) through mpgc::deploy::parse, and what is generated
// from an accepted one for every host (Cyclone config, launch file, links with overrides). The
// input's last line is also tried as a --link and a --cut argument (parse_link, parse_cut).
// Expected rejections: std::runtime_error (parse: file, line, field) and std::invalid_argument
// (parse_link, parse_cut, host_links: the bad word).
#include "deployment.hpp"
#include "fuzz.hpp"

namespace dp = mpgc::deploy;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text = mpgc::fuzz::text(data, size);
  const auto nl = text.find_last_of('\n');
  const std::string last = nl == std::string::npos ? text : text.substr(nl + 1);
  mpgc::fuzz::expect<std::invalid_argument>([&] { (void)dp::parse_link(last).text(); });
  mpgc::fuzz::expect<std::invalid_argument>([&] { (void)dp::parse_cut(last); });
  return mpgc::fuzz::expect<std::runtime_error, std::invalid_argument>([&] {
    const dp::Deployment d = dp::parse(text, "fuzz.yaml");
    dp::LaunchOptions o;
    for (const auto& h : d.hosts) {
      (void)dp::cyclone_config(d, h);
      (void)dp::host_launch(d, h, o);
    }
    for (const auto& c : dp::known_components()) (void)d.host_of(c);
    (void)dp::host_links(d, {last});
  });
}
