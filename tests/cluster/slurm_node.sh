#!/usr/bin/env bash
# A throwaway single-node Slurm cluster for `make check-cluster`: munged, slurmctld and slurmd of
# this machine's Debian packages (slurm-wlm, munge), all under one private folder with their own
# key, sockets, ports and state, run as the calling user (root or not), so that nothing of a
# system-wide Slurm or munge is touched or needed.
#
#   source tests/cluster/slurm_node.sh
#   slurm_node_start DIR     # writes DIR/slurm.conf, starts the daemons, waits for the node; exports SLURM_CONF
#   slurm_node_stop DIR      # stops them (also from a trap)
#
# The node offers the machine's online CPUs and has one partition, "check".

slurm_node_port() {
	# A free TCP port in the ephemeral range, so that two checks on one machine do not collide.
	local port
	for _ in $(seq 1 50); do
		port=$(( (RANDOM % 20000) + 30000 ))
		if ! (exec 3<>"/dev/tcp/127.0.0.1/$port") 2>/dev/null; then
			echo "$port"
			return 0
		fi
	done
	return 1
}

slurm_node_start() {
	local dir=$1
	local user host cpus mem ctld_port slurmd_port
	user=$(id -un)
	host=$(hostname -s)
	cpus=$(nproc)
	mem=$(awk '/MemTotal/ { printf "%d", $2 / 1024 * 0.8 }' /proc/meminfo)
	ctld_port=$(slurm_node_port) || { echo "slurm_node: no free port" >&2; return 1; }
	slurmd_port=$(slurm_node_port) || { echo "slurm_node: no free port" >&2; return 1; }
	mkdir -p "$dir/state" "$dir/spool" "$dir/log" "$dir/munge"
	chmod 700 "$dir/munge"

	# munge: a key of our own, readable by us alone, as munged insists.
	dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
	chmod 400 "$dir/munge/munge.key"
	munged --force --socket="$dir/munge/munge.socket" --key-file="$dir/munge/munge.key" \
		--log-file="$dir/log/munged.log" --pid-file="$dir/munge/munged.pid" \
		--seed-file="$dir/munge/munged.seed" || { echo "slurm_node: munged did not start" >&2; return 1; }

	cat > "$dir/slurm.conf" <<CONF
ClusterName=betelgeuse-check
SlurmctldHost=$host
SlurmUser=$user
SlurmdUser=$user
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/pgid
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
SlurmdTimeout=60
InactiveLimit=0
KillWait=5
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
NodeName=$host CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=check Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
	export SLURM_CONF="$dir/slurm.conf"
	slurmctld -f "$SLURM_CONF" || { echo "slurm_node: slurmctld did not start (log: $dir/log/slurmctld.log)" >&2; return 1; }
	slurmd -f "$SLURM_CONF" || { echo "slurm_node: slurmd did not start (log: $dir/log/slurmd.log)" >&2; return 1; }
	# Until the node takes jobs.
	for _ in $(seq 1 60); do
		if sinfo -h -N -o '%t' 2>/dev/null | grep -qE '^(idle|mix|alloc)'; then
			return 0
		fi
		sleep 1
	done
	echo "slurm_node: the node never came up:" >&2
	sinfo -N 2>&1 | sed 's/^/  /' >&2
	tail -n 20 "$dir/log/slurmctld.log" "$dir/log/slurmd.log" >&2 2>/dev/null
	return 1
}

slurm_node_stop() {
	local dir=$1
	[ -f "$dir/slurm.conf" ] && SLURM_CONF="$dir/slurm.conf" scontrol shutdown >/dev/null 2>&1
	for f in slurmd.pid slurmctld.pid munge/munged.pid; do
		[ -f "$dir/$f" ] && kill "$(cat "$dir/$f")" 2>/dev/null
	done
	sleep 1
	for f in slurmd.pid slurmctld.pid munge/munged.pid; do
		[ -f "$dir/$f" ] && kill -9 "$(cat "$dir/$f")" 2>/dev/null
	done
	return 0
}
