#!/usr/bin/env bash
# Start a single-node Slurm on this machine (Debian/Ubuntu, as root) to try
# scripts/slurm-search.sh; then `cargo test --release --test search_distributed -- --ignored`
# runs the Slurm tests. `scripts/local-slurm.sh stop` stops the daemons it started (by their
# pid files). .ci/run uses it.
set -euo pipefail
if [ "${1:-}" = stop ]; then
    for f in /run/slurmd.pid /run/slurmctld.pid /run/munge/munged.pid; do
        if [ -f "$f" ]; then kill "$(cat "$f")" 2>/dev/null || true; fi
    done
    exit 0
fi
command -v slurmctld >/dev/null || DEBIAN_FRONTEND=noninteractive apt-get install -y -q slurm-wlm
host=$(hostname)
cpus=$(nproc)
mkdir -p /var/lib/slurm/slurmd /var/lib/slurm/slurmctld /var/log/slurm /run/munge
cat > /etc/slurm/slurm.conf <<CONF
ClusterName=local
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
ReturnToService=2
SlurmctldPidFile=/run/slurmctld.pid
SlurmdPidFile=/run/slurmd.pid
SlurmdSpoolDir=/var/lib/slurm/slurmd
StateSaveLocation=/var/lib/slurm/slurmctld
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SlurmctldLogFile=/var/log/slurm/slurmctld.log
SlurmdLogFile=/var/log/slurm/slurmd.log
NodeName=$host CPUs=$cpus State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
chown -R munge:munge /etc/munge /run/munge /var/lib/munge /var/log/munge
# running PIDFILE: the daemon of that pid file is alive (not a zombie left by an earlier run)
running() {
    local state
    state=$(awk '/^State:/ { print $2 }' "/proc/$(cat "$1" 2>/dev/null)/status" 2>/dev/null || true)
    [ -n "$state" ] && [ "$state" != Z ]
}
running /run/munge/munged.pid || su -s /bin/sh munge -c /usr/sbin/munged
running /run/slurmctld.pid || /usr/sbin/slurmctld
sleep 2
running /run/slurmd.pid || /usr/sbin/slurmd
# wait until the node takes jobs (idle), not just until the controller answers
for _ in $(seq 30); do
    [ "$(timeout 5 sinfo -h -o %t 2>/dev/null)" = idle ] && break
    sleep 1
done
sinfo
