/* study.h - the studies: what the papers claim and where the designs stop
 * working, measured by running the testbench engine (testbench/tb.h) many
 * times over a grid, a scene or a list of claims. This header names them
 * all; a file that needs one study includes that study's header.
 *
 *   tb_sweep.h         a unit over widths and settings (threads, shards,
 *                      one CSV), the cheapest formats meeting a target
 *   tb_sweep_check.h   the target search's held-out and derived-range checks
 *   tb_sweep_chart.h   a sweep's charts, drawn from its CSV
 *   tb_span.h          the span units driven with a scene's intervals of any
 *                      length, on the kernel or a batch's lanes
 *   tb_scene.h         a scene shaded through the simulated span hardware
 *                      (images, NMSE, clocks, speed and energy)
 *   tb_scene_search.h  the formats and the grid a scene needs, found by
 *                      rendering it
 *   tb_stability.h     where each method stops working (the stability atlas)
 *   tb_ref_claims.h    the papers' claims on the double references (the
 *                      accuracy rows, and the CPU speed claims for bench/)
 *   tb_speed_hw.h      the papers' speed claims as clocks x area of units
 *   tb_scene_claims.h  the face scene's claims through the hardware
 *   tb_factor_scene.h  the factorization paper's Fig. 1 on a scene,
 *                      through the hf_lookup unit
 *   tb_factor_claims.h the factorization paper's claims
 *   tb_factor_study.h  the factorization's error tables and study series
 *   tb_claims.h        the whole claims table, failure regions, charts
 *
 * Layers: a study uses the engine (testbench/) and the layers below it,
 * never the command line (testbench/cli/), which prints and writes what
 * the studies measure (tests/cli_layers.sh checks it).
 */
#ifndef STUDY_H
#define STUDY_H
#include "testbench/study/tb_sweep.h"
#include "testbench/study/tb_sweep_check.h"
#include "testbench/study/tb_sweep_chart.h"
#include "testbench/study/tb_scene.h"
#include "testbench/study/tb_scene_search.h"
#include "testbench/study/tb_stability.h"
#include "testbench/study/tb_ref_claims.h"
#include "testbench/study/tb_speed_hw.h"
#include "testbench/study/tb_scene_claims.h"
#include "testbench/study/tb_factor_scene.h"
#include "testbench/study/tb_factor_claims.h"
#include "testbench/study/tb_factor_study.h"
#include "testbench/study/tb_claims.h"
#endif
