#include "avar/assembly/pwm_protocol.hpp"

#include <stdexcept>

namespace avar::assembly {

firmware_iface::PwmLinkConfig pwm_config(const rig::Rig& rig, std::size_t link, const std::string& chip) {
  const rig::LinkSpec& spec = rig.links[link];
  firmware_iface::PwmLinkConfig config;
  config.frequency_hz = static_cast<std::uint32_t>(spec.options_as<rig::PwmOptions>().frequency_hz);
  config.description = "PWM link '" + spec.name + "' on " + chip;
  for (const rig::ActuatorSpec& a : rig.actuators_on(rig::LinkIndex{link}))
    config.outputs.push_back({a.channel.value, static_cast<unsigned>(a.device_channel), a.calibration});
  return config;
}

const Protocol& pwm_protocol() {
  static const Protocol p{
      .name = "pwm",
      .open =
          [](const rig::Rig& rig, std::size_t link, LinkEndpoint at) {
            if (!at.pwm) throw std::logic_error("pwm link '" + rig.links[link].name + "' is opened on its PWM chip");
            firmware_iface::PwmLinkConfig config = pwm_config(rig, link, at.pwm->describe());
            OpenedLink opened;
            opened.driver = std::make_unique<firmware_iface::PwmLink>(std::move(at.pwm), std::move(config));
            return opened;
          },
      .make_simulated = nullptr,
      .on_pwm_chip = true,
      .sim =
          {
              .name = "pwm",
              .alias = nullptr,
              .summary = "A simulated PWM chip's outputs driving hobby servos, inside the avar that drives it",
              .description = "A PWM chip (a Raspberry Pi's hardware PWM through sysfs) whose outputs each send a hobby servo "
                             "one pulse per period; the servos' positions are what their pulses say. A simulated chip has no "
                             "files another program could open: it lives inside the avar process that drives it. Give the link "
                             "port: sim in the rig, or run with --sim.",
              .transport = SimTransport::in_process,
              .example = "  avar play examples/shows/hello-head.yaml --rig examples/rigs/pin-servo-head.yaml --sim",
              .options = {},
          },
  };
  return p;
}

}  // namespace avar::assembly
