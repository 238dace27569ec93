#!/usr/bin/env bash
# The monitor's costs on this machine, a simulated ship (`moorsim stream`) playing to it over
# UDP on loopback:
#   benchmarks/monitor.sh latency OUT   10 Hz position and heading, 8 cells at 1 Hz, thrust,
#                                       real time, 480 s of the thesis line-6 case: the
#                                       latency from a line's arrival to its events and ALR
#   benchmarks/monitor.sh cpu OUT       the same vessel at 1 Hz, real time, 600 s, no failure:
#                                       the monitor's CPU (share of one core) and RSS
#   benchmarks/monitor.sh soak OUT      24 simulated hours at 100 times real time (14.4 min):
#                                       the monitor's RSS every 30 s, hour 1 against hour 24
# Each writes OUT/<kind>.json with the numbers and the monitor's own summary (stderr).
# MOORSIM (default build/release/tools/moorsim) is the program measured.
set -euo pipefail
kind=${1:?usage: benchmarks/monitor.sh latency|cpu|soak OUT}
out=${2:?usage: benchmarks/monitor.sh latency|cpu|soak OUT}
root="$(cd "$(dirname "$0")/.." && pwd)"
moorsim=${MOORSIM:-$root/build/release/tools/moorsim}
mkdir -p "$out"
work=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$work"' EXIT
port=$(python3 -c 'import socket; s=socket.socket(socket.AF_INET, socket.SOCK_DGRAM); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
bridge=$(python3 -c 'import socket; s=socket.socket(socket.AF_INET, socket.SOCK_DGRAM); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
library=$root/scenarios/library
case $kind in
  latency)
    rate=10 speed=1 duration=480 base=thesis_line6.yaml timing=arrival ;;
  cpu)
    rate=1 speed=1 duration=600 base=thesis_no_failure.yaml timing=arrival ;;
  soak)
    rate=1 speed=100 duration=86400 base=thesis_no_failure.yaml timing=tags ;;
  *) echo "unknown kind '$kind' (latency, cpu or soak)" >&2; exit 2 ;;
esac
sensors="sensors:
  gnss: {rate_hz: $rate}
  gyro: {rate_hz: $rate}
  tension_cells: {rate_hz: 1, noise: {std_dev: 1.0e4}}"
printf 'base: %s\n%s\n' "$library/thesis_no_failure.yaml" "$sensors" > "$work/vessel.yaml"
printf 'base: %s\n%s\n' "$library/$base" "$sensors" > "$work/trial.yaml"
{
  echo "scenario: vessel.yaml"
  echo "origin: {latitude_deg: 61.25, longitude_deg: 1.75}"
  echo "antenna: [40, -5, -30]"
  echo "feeds:"
  echo "  - {name: ship, udp: {address: 127.0.0.1, port: $port}, timing: $timing}"
  echo "cells:"
  for k in 1 2 3 4 5 6 7 8; do echo "  - {transducer: LC$k, line: $k}"; done
  echo "thrust: {feed: ship, transducers: [TX, TY, TN]}"
  echo "store: store"
  echo "alarms: alarms.jsonl"
  echo "bridge: {send: 127.0.0.1:$bridge}"
} > "$work/monitor.yaml"

cd "$work"
"$moorsim" monitor monitor.yaml 2> monitor.err &
monitor=$!
sleep 3
start=$(date +%s.%N)
"$moorsim" stream trial.yaml --to monitor.yaml --speed "$speed" \
  --set simulation.duration="$duration" 2> stream.err &
stream=$!
# The monitor's CPU time and RSS every 30 s while the ship plays.
python3 - "$monitor" "$stream" > usage.json <<'EOF'
import json, os, sys, time
monitor, stream = int(sys.argv[1]), int(sys.argv[2])
tick = os.sysconf("SC_CLK_TCK")
def cpu():
    fields = open(f"/proc/{monitor}/stat").read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / tick
def rss():
    for line in open(f"/proc/{monitor}/status"):
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024.0
rows = []
t0, c0 = time.time(), cpu()
while True:
    try:
        os.kill(stream, 0)
        done = open(f"/proc/{stream}/stat").read().rsplit(")", 1)[1].split()[0] == "Z"
    except OSError:
        done = True
    rows.append({"wall_s": round(time.time() - t0, 1), "cpu_s": cpu() - c0, "rss_mb": rss()})
    if done:
        break
    time.sleep(30)
json.dump(rows, sys.stdout)
EOF
wait "$stream"
kill -TERM "$monitor"
wait "$monitor" || true
python3 - "$kind" "$duration" "$speed" > "$out/$kind.json" <<'EOF'
import json, sys
kind, duration, speed = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
rows = json.load(open("usage.json"))
err = open("monitor.err").read()
summary = err.strip().splitlines()[-1]
last = rows[-1]
result = {"kind": kind, "simulated_s": duration, "speed": speed,
          "wall_s": last["wall_s"], "cpu_share_of_one_core": last["cpu_s"] / max(last["wall_s"], 1e-9),
          "rss_mb": [r["rss_mb"] for r in rows], "monitor_summary": summary}
# Hour 1 and hour 24 of a soak: the RSS at the first sample past each.
if kind == "soak":
    per_hour = 3600.0 / speed
    first = next(r for r in rows if r["wall_s"] >= per_hour)
    result["rss_hour_1_mb"], result["rss_hour_24_mb"] = first["rss_mb"], last["rss_mb"]
json.dump(result, sys.stdout, indent=1)
EOF
cp alarms.jsonl "$out/$kind-alarms.jsonl"
cp monitor.err "$out/$kind-monitor.err"
cat "$out/$kind.json"
