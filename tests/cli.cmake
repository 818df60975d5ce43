# The amsph command line, end to end: run the README example, then each
# kind of bad input must exit with status 2 and say what is wrong.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

function(expect_status expected)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL expected)
    message(FATAL_ERROR "`${ARGN}` exited ${status}, expected ${expected}\n${out}\n${err}")
  endif()
  set(last_output "${out}${err}" PARENT_SCOPE)
endfunction()

function(expect_text text)
  string(FIND "${last_output}" "${text}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "expected the output to contain '${text}', got:\n${last_output}")
  endif()
endfunction()

expect_status(0 ${AMSPH} run ${SOURCE}/cases/examples/falling_block_2d.yaml -o ${WORK}/run --quiet)
foreach(f snap_000000.h5 snapshots.xmf)
  if(NOT EXISTS ${WORK}/run/${f})
    message(FATAL_ERROR "amsph run wrote no ${f}")
  endif()
endforeach()

expect_status(2 ${AMSPH} check ${WORK}/does_not_exist.yaml)
expect_text("does_not_exist.yaml")
file(WRITE ${WORK}/bad.yaml "dimension: 4\n")
expect_status(2 ${AMSPH} check ${WORK}/bad.yaml)
expect_text("bad.yaml:1:")
expect_status(2 ${AMSPH} run ${SOURCE}/cases/examples/falling_block_2d.yaml)
expect_text("-o OUTDIR")
expect_status(2 ${AMSPH} run ${SOURCE}/cases/examples/falling_block_2d.yaml -o ${WORK}/x --backend cuda)
expect_text("--backend takes openmp or opencl")
expect_status(2 ${AMSPH} run ${SOURCE}/cases/examples/falling_block_2d.yaml -o "")
expect_text("-o needs a directory")
# Integers beyond an option's range (or beyond 64 bits) are bad usage, not
# wrapped or clamped into it.
expect_status(2 ${AMSPH} run ${SOURCE}/cases/examples/falling_block_2d.yaml -o ${WORK}/x --device 4294967296)
expect_text("--device takes a device index from 0 to 2147483647: 4294967296")
expect_status(2 ${AMSPH} run ${SOURCE}/cases/examples/falling_block_2d.yaml -o ${WORK}/x --max-steps 99999999999999999999)
expect_text("--max-steps takes a step count from 1 to 9223372036854775807: 99999999999999999999")
# Geometry blocks that would place particles on top of each other are bad
# input for check and run alike; a `fill` block fills around the others.
set(overlap "dimension: 2\ndomain: {min: [0, 0], max: [1, 1]}\ndx: 0.05\nend_time: 0.01
output_interval: 0.01\nmaterials:\n  - {name: water, density: 1000, sound_speed: 10}\ngeometry:
  - {shape: box, kind: fluid, material: water, min: [0.1, 0.1], max: [0.5, 0.5]}
  - {shape: box, kind: fluid, material: water, min: [0.3, 0.3], max: [0.7, 0.7]SECOND}\n")
string(REPLACE "SECOND" "" text "${overlap}")
file(WRITE ${WORK}/overlap.yaml "${text}")
expect_status(2 ${AMSPH} check ${WORK}/overlap.yaml)
expect_text("overlap.yaml:10: geometry block places a particle at (0.325, 0.325, 0) m within 0.3 dx")
expect_status(2 ${AMSPH} run ${WORK}/overlap.yaml -o ${WORK}/x --quiet)
expect_text("the blocks overlap")
string(REPLACE "SECOND" ", fill: true" text "${overlap}")
file(WRITE ${WORK}/overlap_fill.yaml "${text}")
expect_status(0 ${AMSPH} check ${WORK}/overlap_fill.yaml)
expect_text("2 geometry blocks, 112 particles)") # 8 x 8 each, less the 4 x 4 shared
# A `fill` block on a lattice offset from the one before it (0.4 dx here)
# would skip a whole layer along their common face: bad input.
string(REPLACE "[0.3, 0.3], max: [0.7, 0.7]SECOND" "[0.32, 0.3], max: [0.72, 0.7], fill: true" text "${overlap}")
file(WRITE ${WORK}/offset_fill.yaml "${text}")
expect_status(2 ${AMSPH} check ${WORK}/offset_fill.yaml)
expect_text("offset_fill.yaml:10: this fill block's lattice is offset from that of a block before it: its point (0.345, 0.325, 0) m lies 0.40 dx from a particle there, so the fill would leave a gap of up to 1.40 dx along their common faces; move this block by (-0.02, 0, 0) m")
string(REPLACE "0.7, 0.7]SECOND" "0.32, 0.32]" text "${overlap}")
file(WRITE ${WORK}/empty_block.yaml "${text}")
expect_status(2 ${AMSPH} check ${WORK}/empty_block.yaml)
expect_text("empty_block.yaml:10: geometry block holds no particle at dx = 0.05 m")
# Grains that start closer than the contact distance to another grain are
# bad input: two discs of 2 dx sampled about their own centres, their
# nearest particles 0.4 dx apart (centres 0.17 apart), then 1 dx (0.2).
set(pressed "dimension: 2\ndomain: {min: [0, 0], max: [1, 1]}\ndx: 0.05\nend_time: 0.01
output_interval: 0.01\nfluid: {}\ngrains: {contact_stiffness: 1.0e3, contact_damping: 0.1}
materials:\n  - {name: steel, density: 7000, sound_speed: 10}\ngeometry:
  - {shape: circle, kind: grain, material: steel, center: [0.3, 0.5], radius: 0.1}
  - {shape: circle, kind: grain, material: steel, center: [SECOND, 0.5], radius: 0.1}\n")
string(REPLACE "SECOND" "0.47" text "${pressed}")
file(WRITE ${WORK}/pressed.yaml "${text}")
expect_status(2 ${AMSPH} check ${WORK}/pressed.yaml)
expect_text("pressed.yaml:11: a grain particle at (0.375, 0.475, 0) m starts 0.4 dx from a particle of another grain")
string(REPLACE "SECOND" "0.5" text "${pressed}")
file(WRITE ${WORK}/apart.yaml "${text}")
expect_status(0 ${AMSPH} check ${WORK}/apart.yaml)
# A scene's size is checked before it is walked: two small blocks 25 m from
# the origin at dx = 1 mm (6.25e8 cells of dx in the domain, which the
# overlap test used to allocate; beyond 2^31 of them it crashed) build at
# once, and a block of 4e10 lattice points (a tank of 100000 wall layers)
# is refused instead of walked. A dx finer than the float positions resolve
# in the domain is refused first.
set(far "dimension: 2\ndomain: {min: [0, 0], max: [25, 25]}\ndx: 1.0e-3\nend_time: 0.01
output_interval: 0.01\nmaterials:\n  - {name: water, density: 1000}\ngeometry:
  - {shape: box, kind: fluid, material: water, min: [24.9, 24.9], max: [24.91, 24.91]}
  - {shape: box, kind: fluid, material: water, min: [24.95, 24.9], max: [24.96, 24.91]}\n")
file(WRITE ${WORK}/far.yaml "${far}")
expect_status(0 ${AMSPH} check ${WORK}/far.yaml)
expect_text("2 geometry blocks, 200 particles)")
file(WRITE ${WORK}/huge_block.yaml "dimension: 2\ndomain: {min: [0, 0], max: [1, 1]}\ndx: 0.05
end_time: 0.01\noutput_interval: 0.01\nmaterials:\n  - {name: water, density: 1000}\ngeometry:
  - {shape: box, kind: wall, material: water, min: [0.1, 0.1], max: [0.9, 0.9], layers: 100000}\n")
expect_status(2 ${AMSPH} check ${WORK}/huge_block.yaml)
expect_text("huge_block.yaml:9: geometry block spans 4e+10 lattice points at dx = 0.05 m")
string(REPLACE "SECOND" "" text "${overlap}")
string(REPLACE "dx: 0.05" "dx: 1.0e-7" text "${text}")
file(WRITE ${WORK}/too_fine.yaml "${text}")
expect_status(2 ${AMSPH} check ${WORK}/too_fine.yaml)
expect_text("too_fine.yaml:2: the domain reaches 1 m from the origin along x, where the particles' positions")
# A state that blows up stops the run with the last good state written, in
# every module: a thermal-only run whose laser overflows the enthalpy
# (1e30 W) used to run on with a temperature of NaN (test_fluid checks the
# positions that turn NaN).
set(hot "dimension: 2\ndomain: {min: [-1.0e-4, -1.0e-4], max: [1.1e-3, 6.0e-4]}\ndx: 4.0e-5
end_time: 1.0e-4\noutput_interval: 5.0e-5\nthermal: {}\nmaterials:
  - {name: steel, density: 7000, specific_heat: 700, conductivity: 30}\ngeometry:
  - {shape: box, kind: solid, material: steel, min: [0, 0], max: [1.0e-3, 4.0e-4], temperature: 300}
laser: {power: 1e30, radius: 1.0e-4, absorption: surface, absorptivity: 0.5, start: [5.0e-4, 4.0e-4]}\n")
file(WRITE ${WORK}/overheated.yaml "${hot}")
expect_status(1 ${AMSPH} run ${WORK}/overheated.yaml -o ${WORK}/overheated --force --quiet)
expect_text("guard 'finite values' failed: step 1, t = ")
expect_text("the last good state (step 0, t = 0 s) is")
# A first step the run could never finish with is bad input naming its
# limit (conductivity 1e30: a step of 1e-33 s; it used to run on for ever).
string(REPLACE "conductivity: 30" "conductivity: 1e30" text "${hot}")
string(REPLACE "power: 1e30" "power: 100" text "${text}")
file(WRITE ${WORK}/conductor.yaml "${text}")
expect_status(2 ${AMSPH} run ${WORK}/conductor.yaml -o ${WORK}/conductor --force --quiet)
expect_text("the first time step is 1.13e-33 s (diffusion limit), 8.86e+28 steps to end_time")
# What the run finds wrong with the case when it lays out its grids is bad
# input (exit 2), as the parser's findings are, and `check` finds it too.
file(READ ${SOURCE}/cases/validation/laser_slab_2d.yaml text)
string(REPLACE "  power: 100\n  radius: 1.0e-4" "  power: 100\n  radius: 2.0e-3\n  bin_size: 1.0e-3" text "${text}")
file(WRITE ${WORK}/coarse_bins.yaml "${text}")
expect_status(2 ${AMSPH} run ${WORK}/coarse_bins.yaml -o ${WORK}/coarse_bins --force --quiet)
expect_text("laser.bin_size 0.001 m is too large")
expect_status(2 ${AMSPH} check ${WORK}/coarse_bins.yaml)
expect_text("laser.bin_size 0.001 m is too large")
string(REPLACE "SECOND" "" text "${overlap}")
string(REPLACE "domain: {min: [0, 0], max: [1, 1]}" "domain: {min: [0, 0], max: [0.3, 1], periodic: [true, false]}"
       text "${text}")
string(REPLACE "max: [0.5, 0.5]}" "max: [0.3, 0.5]}" text "${text}")
file(WRITE ${WORK}/short_periodic.yaml "${text}")
expect_status(2 ${AMSPH} check ${WORK}/short_periodic.yaml)
expect_text("periodic axis x: the domain length 0.3 m is shorter than 3 kernel supports")
expect_status(2 ${AMSPH} frobnicate)
expect_text("unknown command")
expect_status(0 ${AMSPH} --help)
expect_text("run CASE.yaml -o OUTDIR")
expect_status(0 ${AMSPH} devices)
expect_text("openmp")

set(example ${SOURCE}/cases/examples/falling_block_2d.yaml)

# An output directory that holds files is kept unless --force; one that
# cannot be created is a run failure that says why.
expect_status(2 ${AMSPH} run ${example} -o ${WORK}/run --quiet)
expect_text("already holds files")
expect_status(0 ${AMSPH} run ${example} -o ${WORK}/run --quiet --force)
file(WRITE ${WORK}/plain "not a directory")
expect_status(2 ${AMSPH} run ${example} -o ${WORK}/plain --quiet)
expect_text("is not a directory")
expect_status(1 ${AMSPH} run ${example} -o ${WORK}/plain/out --quiet)
expect_text("cannot create directory")

# Progress: plain lines when stderr is not a terminal, nothing with --quiet,
# one line updated in place on a terminal (script(1) gives it one).
expect_status(0 ${AMSPH} run ${example} -o ${WORK}/progress)
expect_text("particle-steps/s  ETA 0:00:00\n")
expect_text("amsph: done")
expect_status(0 ${AMSPH} run ${example} -o ${WORK}/quiet --quiet)
if(NOT last_output STREQUAL "")
  message(FATAL_ERROR "--quiet printed:\n${last_output}")
endif()
find_program(SCRIPT script)
if(SCRIPT)
  expect_status(0 ${SCRIPT} -qec "${AMSPH} run ${example} -o ${WORK}/terminal" /dev/null)
  string(ASCII 13 cr)
  string(ASCII 27 esc)
  expect_text("${cr}t = ")
  expect_text("ETA 0:00:00${esc}[K\n")
endif()

# Stop at a step count, restart elsewhere and in place; bad restarts are
# bad input that says why.
set(dambreak "dimension: 2\ndomain: {min: [-0.05, -0.05], max: [0.634, 0.45]}\ndx: 0.0146
end_time: END\noutput_interval: 0.005\ngravity: [0.0, -9.81]
fluid: {viscosity: artificial, artificial_alpha: 0.1, tensile_correction: 0.1}
materials:\n  - {name: water, density: 1000, viscosity: 1.0e-3, sound_speed: 25}
geometry:
  - {shape: box, kind: wall, material: water, min: [0, 0], max: [0.584, 0.38], layers: 3, open: [+y]}
  - {shape: box, kind: fluid, material: water, min: [0, 0], max: [0.146, 0.292], hydrostatic: true}\n")
string(REPLACE "END" "0.4" text "${dambreak}")
file(WRITE ${WORK}/dambreak.yaml "${text}")
set(dambreak_case ${WORK}/dambreak.yaml)
expect_status(0 ${AMSPH} run ${dambreak_case} -o ${WORK}/stop --max-steps 30)
expect_text("stopped at step 30")
# a checkpoint interval that reads as simulated time is wall time: said, even quiet
expect_status(0 ${AMSPH} run ${dambreak_case} -o ${WORK}/often --max-steps 3 --checkpoint-interval 1e-6 --quiet)
expect_text("--checkpoint-interval 1e-06 is in seconds of wall time, not simulated time")
execute_process(COMMAND ${CMAKE_COMMAND} -E copy ${WORK}/stop/checkpoint.h5 ${WORK}/stop/step30.h5)
expect_status(0 ${AMSPH} run ${dambreak_case} -o ${WORK}/elsewhere --max-steps 60 --restart ${WORK}/stop/checkpoint.h5 --quiet)
expect_status(0 ${AMSPH} run ${dambreak_case} -o ${WORK}/stop --max-steps 60 --restart ${WORK}/stop/checkpoint.h5 --quiet)
foreach(f stop/snap_000004.h5 stop/series.csv elsewhere/snap_000004.h5 elsewhere/checkpoint.h5)
  if(NOT EXISTS ${WORK}/${f})
    message(FATAL_ERROR "no ${f} after the restarts")
  endif()
endforeach()
expect_status(2 ${AMSPH} run ${dambreak_case} -o ${WORK}/x --max-steps 50 --restart ${WORK}/stop/checkpoint.h5)
expect_text("is at step 60 already")
expect_status(2 ${AMSPH} run ${dambreak_case} -o ${WORK}/x --restart ${WORK}/stop/snap_000000.h5)
expect_text("not an amsph checkpoint")
expect_status(2 ${AMSPH} run ${example} -o ${WORK}/x --restart ${WORK}/stop/checkpoint.h5)
expect_text("written for another case")
expect_status(2 ${AMSPH} run ${dambreak_case} -o ${WORK}/x --restart ${WORK}/nothing.h5)
expect_text("cannot open the restart file")
# Restarted in place from an earlier checkpoint, the run removes the
# snapshots written after it (snap_000004.h5 of the run to step 60).
expect_status(0 ${AMSPH} run ${dambreak_case} -o ${WORK}/stop --max-steps 31 --restart ${WORK}/stop/step30.h5 --quiet)
if(EXISTS ${WORK}/stop/snap_000004.h5 OR NOT EXISTS ${WORK}/stop/snap_000003.h5)
  message(FATAL_ERROR "the restart from step 30 left snap_000004.h5 or wrote no snap_000003.h5")
endif()

# --force replaces the run in a directory: a shorter run leaves none of the
# longer one's snapshots for analyze to read, and other files stay.
foreach(end 0.02 0.01)
  string(REPLACE "END" "${end}" text "${dambreak}")
  file(WRITE ${WORK}/dambreak_${end}.yaml "${text}")
endforeach()
expect_status(0 ${AMSPH} run ${WORK}/dambreak_0.02.yaml -o ${WORK}/forced --quiet)
file(WRITE ${WORK}/forced/notes.txt "kept")
expect_status(0 ${AMSPH} run ${WORK}/dambreak_0.01.yaml -o ${WORK}/forced --quiet --force)
if(EXISTS ${WORK}/forced/snap_000003.h5 OR NOT EXISTS ${WORK}/forced/notes.txt)
  message(FATAL_ERROR "--force left snap_000003.h5 of the earlier run or removed notes.txt")
endif()
expect_status(0 ${AMSPH} analyze ${WORK}/forced)
file(STRINGS ${WORK}/forced/melt_pool.csv rows)
list(LENGTH rows n_rows)
if(NOT n_rows EQUAL 4) # the header and t = 0, 0.005, 0.01
  message(FATAL_ERROR "analyze after --force read ${n_rows} rows, expected 4")
endif()

# SIGTERM (and SIGINT, the same handler) stops a run with a checkpoint and a
# final snapshot; the exit status is 128 + the signal number.
find_program(TIMEOUT timeout)
if(TIMEOUT)
  string(REPLACE "END" "1000" text "${dambreak}")
  file(WRITE ${WORK}/long.yaml "${text}")
  # --foreground: timeout signals amsph once (else once more through the process group).
  expect_status(143 ${TIMEOUT} --foreground --preserve-status -s TERM 1 ${AMSPH} run ${WORK}/long.yaml -o ${WORK}/signal)
  expect_text("stopped by signal 15")
  if(NOT EXISTS ${WORK}/signal/checkpoint.h5)
    message(FATAL_ERROR "SIGTERM left no checkpoint")
  endif()
  # An ETA too long for h:mm:ss (here 1e8 s of simulated time: 840 days at the
  # 7934 steps/s of an idle CI machine, where 1e7 s read 86 days) is ">99 days".
  string(REPLACE "END" "1e8" text "${dambreak}")
  string(REPLACE "output_interval: 0.005" "output_interval: 100" text "${text}")
  file(WRITE ${WORK}/endless.yaml "${text}")
  expect_status(143 ${TIMEOUT} --foreground --preserve-status -s TERM 1 ${AMSPH} run ${WORK}/endless.yaml -o ${WORK}/endless)
  expect_text("ETA >99 days\n")
endif()

# amsph bench throughput: a tiny run prints its table (tests/test_bench.c
# checks the numbers' structure); bad input exits with status 2.
set(dambreak_2d ${SOURCE}/cases/validation/dambreak_2d.yaml)
expect_status(0 ${AMSPH} bench throughput ${dambreak_2d} --particles 500 --warmup 0 --steps 1)
expect_text("| particles | ms/step | particle-steps/s | device bytes/particle | sort |")
expect_status(2 ${AMSPH} bench throughput)
expect_text("a case file is needed")
expect_status(2 ${AMSPH} bench frobnicate)
expect_text("bench knows: grid, throughput")
expect_status(2 ${AMSPH} bench throughput ${dambreak_2d} --particles 1.5)
expect_text("--particles takes a count from 1 to 2e9: 1.5")
expect_status(2 ${AMSPH} bench throughput ${dambreak_2d} --steps 0)
expect_text("--steps takes a count from 1 to 1000000: 0")
expect_status(2 ${AMSPH} bench throughput ${dambreak_2d} --csv ${WORK}/plain/bench.csv)
expect_text("cannot write ${WORK}/plain/bench.csv")

# README.md carries the series.csv column reference that `amsph columns` prints.
execute_process(COMMAND ${AMSPH} columns OUTPUT_VARIABLE columns RESULT_VARIABLE status)
file(READ ${SOURCE}/README.md readme)
string(FIND "${readme}" "${columns}" at)
if(NOT status EQUAL 0 OR at EQUAL -1)
  message(FATAL_ERROR "README.md lacks the output of `amsph columns`:\n${columns}")
endif()

# README.md carries the melt-pool metric reference that `amsph analyze --metrics` prints.
execute_process(COMMAND ${AMSPH} analyze --metrics OUTPUT_VARIABLE metrics RESULT_VARIABLE status)
string(FIND "${readme}" "${metrics}" at)
if(NOT status EQUAL 0 OR at EQUAL -1)
  message(FATAL_ERROR "README.md lacks the output of `amsph analyze --metrics`:\n${metrics}")
endif()

# The analysis of the README example's run; bad input exits 2.
expect_status(0 ${AMSPH} analyze ${WORK}/run --csv ${WORK}/run_pool.csv)
file(READ ${WORK}/run_pool.csv pool)
if(NOT pool MATCHES "^time,melt_particles,")
  message(FATAL_ERROR "amsph analyze wrote no header to ${WORK}/run_pool.csv:\n${pool}")
endif()
expect_status(2 ${AMSPH} analyze)
expect_text("analyze needs an output directory")
expect_status(2 ${AMSPH} analyze ${WORK}/plain_dir_without_snapshots)
expect_text("holds no snapshot")
expect_status(2 ${AMSPH} analyze ${WORK}/run --scan w)
expect_text("--scan takes x, y or z: w")
expect_status(2 ${AMSPH} analyze ${WORK}/run --up x)
expect_text("must be two different axes")
file(MAKE_DIRECTORY ${WORK}/not_hdf5)
file(WRITE ${WORK}/not_hdf5/snap_000000.h5 "")
expect_status(2 ${AMSPH} analyze ${WORK}/not_hdf5)
expect_text("${WORK}/not_hdf5/snap_000000.h5 is not a readable HDF5 snapshot")

# README.md documents every case-file key that `amsph keys` knows.
execute_process(COMMAND ${AMSPH} keys OUTPUT_VARIABLE keys RESULT_VARIABLE status)

# An unknown key's message lists every key of its section, even the longest
# list (materials[]).
string(REGEX MATCHALL "\\| `materials\\[\\]\\.[a-z_]+`" rows "${keys}")
string(REGEX REPLACE "\\| `materials\\[\\]\\.([a-z_]+)`" "\\1" material_keys "${rows}")
string(REPLACE ";" ", " material_keys "${material_keys}")
file(WRITE ${WORK}/unknown_material_key.yaml "dimension: 2\ndomain: {min: [0, 0], max: [1, 1]}\ndx: 0.05
end_time: 0.01\noutput_interval: 0.01\nmaterials:\n  - {name: water, density: 1000, zzzzqqqq: 1}\n")
expect_status(2 ${AMSPH} check ${WORK}/unknown_material_key.yaml)
expect_text("unknown key 'zzzzqqqq' in materials[0] (allowed: ${material_keys})\n")
string(REPLACE "\n" ";" rows "${keys}")
foreach(row ${rows})
  if(row MATCHES "^\\| `([^`]+)`")
    string(FIND "${readme}" "`${CMAKE_MATCH_1}`" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "README.md does not document the case key `${CMAKE_MATCH_1}`")
    endif()
  endif()
endforeach()
