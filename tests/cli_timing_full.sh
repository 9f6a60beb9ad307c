#!/bin/sh
# cli_timing_full.sh - tests/cli_timing.sh over every unit at widths 8, 16
# and 24 (TIMING_DESIGNS=all): the Yosys longest-path comparison whose
# table docs/timing.md shows. Minutes of CPU: `make test-long` runs it;
# make test runs cli_timing at width 8 alone.
TIMING_DESIGNS=all exec sh tests/cli_timing.sh
