# examples/deposit/check_steps_postpro.cmake — the POSTPRO columns of deposit's steps.csv
# (issue #11, docs/output.md): after the columns of before (the last of which is step_s), then
# the threads each step ran on (issue #37), and
# consistent in every row: the status counts add up to `contacts`, stick + slips to `active`,
# the strong and weak networks to `active`; once forces act, the cumulative contact dissipation
# is a positive number.
#   cmake -DFILE=<steps.csv> -P check_steps_postpro.cmake
if(NOT EXISTS "${FILE}")
  message(FATAL_ERROR "'${FILE}' does not exist")
endif()
file(STRINGS "${FILE}" lines)
list(POP_FRONT lines header)
string(REPLACE "," ";" columns "${header}")
set(expected_tail step_s kinetic_energy contact_dissipation contact_dissipation_step coordination_number sliding_share
    strong_contacts weak_contacts strong_force_share weak_force_share status_open status_stick status_slip_forward
    status_slip_backward solve_threads loop_threads)
list(FIND columns step_s first)
list(LENGTH columns n)
list(SUBLIST columns ${first} -1 tail)
if(first LESS 0 OR NOT tail STREQUAL expected_tail)
  message(FATAL_ERROR "'${FILE}': the columns after step_s are '${tail}', expected '${expected_tail}'")
endif()
foreach(name contacts active contact_dissipation strong_contacts weak_contacts status_open status_stick status_slip_forward
        status_slip_backward)
  list(FIND columns ${name} i_${name})
endforeach()
set(row_no 1)
set(last_dissipation "")
foreach(line IN LISTS lines)
  math(EXPR row_no "${row_no} + 1")
  string(REPLACE "," ";" f "${line}")
  foreach(name contacts active strong_contacts weak_contacts status_open status_stick status_slip_forward status_slip_backward)
    list(GET f ${i_${name}} v_${name})
  endforeach()
  list(GET f ${i_contact_dissipation} last_dissipation)
  math(EXPR statuses "${v_status_open} + ${v_status_stick} + ${v_status_slip_forward} + ${v_status_slip_backward}")
  math(EXPR pressed "${v_status_stick} + ${v_status_slip_forward} + ${v_status_slip_backward}")
  math(EXPR networks "${v_strong_contacts} + ${v_weak_contacts}")
  if(NOT statuses EQUAL v_contacts OR NOT pressed EQUAL v_active OR NOT networks EQUAL v_active)
    message(FATAL_ERROR "'${FILE}' line ${row_no}: contacts ${v_contacts}, active ${v_active}, statuses add up to ${statuses} "
      "(pressed ${pressed}), strong + weak = ${networks}")
  endif()
endforeach()
if(NOT last_dissipation MATCHES "^[0-9]+(\\.[0-9]+)?(e[-+][0-9]+)?$" OR last_dissipation MATCHES "^0(\\.0*)?$")
  message(FATAL_ERROR "'${FILE}': the last contact_dissipation is '${last_dissipation}', expected a positive number")
endif()
message(STATUS "${row_no} lines consistent; contact_dissipation at the end ${last_dissipation} J/m")
