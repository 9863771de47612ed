# The simulated sessions of each bus that the benchmark times (bench/run) and the profile-guided
# package trains on (scripts/pgo-train): `dpscope simulate` arguments after --bus, -w, --cycles,
# -c and --seed, which each script chooses (the benchmark seed 7 and its sizes; the training
# seed 11 and 200 k telegrams). Sourced by both, so that the training stays on the benchmark's
# kinds when these change.

# Cyclic PROFIBUS DP (--bus profibus): five slaves, PPO types 1, 2, 5 and 3 and a PROFIdrive one,
# rejected requests, FCS errors and stacked requests at a rate.
profibus_session=(--slave 3:1 --slave 4:2 --slave 5:5 --slave 6:3 --slave 7:1:profidrive
    --fault request_rejected=0.0005 --fault fcs_error=0.0002 --fault stacked_request=0.0002)

# The DP-V1 mix (--bus profibus): the same slaves, three of them DP-V1 (about a quarter of the
# telegrams are MSAC_C1), negative responses and error PDUs at a rate.
dpv1_session=(--slave 3:1 --slave 4:2:dpv1 --slave 5:5 --slave 6:3:dpv1
    --slave 7:1:profidrive:dpv1
    --fault request_rejected=0.0005 --fault fcs_error=0.0002
    --fault dpv1_negative_response=0.002 --fault dpv1_error_pdu=0.0002)

# Danfoss FC protocol (--bus fc): five drives, both address formats, the FC faults at a rate.
fc_session=(--drive 1 --drive 2 --drive 3:1-31 --drive 17:1-31 --drive 100
    --fault fc_bcc_error=0.0005 --fault fc_no_response=0.0005
    --fault fc_late_response=0.0005 --fault fc_command_rejected=0.001
    --fault fc_stacked_request=0.0002 --fault fc_mismatched_response=0.0002
    --fault fc_unexpected_response_type=0.0002 --fault garbage=0.0002
    --fault malformed_telegram=0.0002)

# VLT 2000 (--bus vlt2000): five drives, the VLT 2000 faults at a rate.
vlt2000_session=(--drive 1 --drive 2 --drive 5 --drive 17 --drive 31
    --fault vlt2000_checksum_error=0.0005 --fault vlt2000_no_response=0.0005
    --fault vlt2000_command_failed=0.001 --fault vlt2000_stacked_request=0.0002
    --fault vlt2000_mismatched_response=0.0002
    --fault vlt2000_unexpected_reply=0.0002 --fault garbage=0.0002
    --fault malformed_telegram=0.0002)
