// The `replay` and `record` subcommands of flat2d-inspect: a capture's payloads to a
// UDP address with their original timing, and live sensor packets into a pcap file.
#pragma once

namespace flat2d::maps {

// flat2d-inspect replay [--to ADDR[:PORT]] [--speed X] [--count N] [--all-ports] CAPTURE
int RunReplay(int argc, char** argv);

// flat2d-inspect record --out FILE [--bind ADDR] [--port P] [--position-port P]
//   [--multicast GROUP] [--source ADDR] [--rcvbuf BYTES] [--seconds S] [--count N]
int RunRecord(int argc, char** argv);

}  // namespace flat2d::maps
