#!/usr/bin/env bash
# The ensemble example sharded over a real Slurm cluster of one node on
# localhost: Debian's slurm-wlm and munge installed if missing, the
# daemons started, the example submitted as a 4-task array job with the
# merge as a job that depends on it, and the merged final states checked
# byte for byte against the unsharded run (the CSV writes every number
# in its shortest exact form, so equal bytes are equal bits).
#
# Needs root (it installs packages and starts daemons) and the example
# built (`cargo build --example ensemble`; `cargo test` builds it).
# The guide's chapter on ensembles gives the same recipe for a real
# cluster.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
members=${MEMBERS:-2000}
ensemble=${ENSEMBLE:-$root/target/debug/examples/ensemble}
[ -x "$ensemble" ] || cargo build --example ensemble

if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
    export DEBIAN_FRONTEND=noninteractive
    # Nothing starts while the packages install: the daemons are started
    # below, with this configuration.
    printf '#!/bin/sh\nexit 101\n' >/usr/sbin/policy-rc.d
    chmod +x /usr/sbin/policy-rc.d
    apt-get update -qq
    apt-get install -y -qq slurm-wlm munge >/dev/null
    rm -f /usr/sbin/policy-rc.d
fi

work=$(mktemp -d /tmp/daegen-slurm.XXXXXX)
host=$(hostname -s)
mkdir -p /etc/slurm /var/spool/slurmctld /var/spool/slurmd /var/log/slurm /run/munge
cat >/etc/slurm/slurm.conf <<CONF
ClusterName=daegen
SlurmctldHost=${host}(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation=/var/spool/slurmctld
SlurmdSpoolDir=/var/spool/slurmd
SlurmctldPidFile=/run/slurmctld.pid
SlurmdPidFile=/run/slurmd.pid
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MinJobAge=600
SlurmctldLogFile=/var/log/slurm/slurmctld.log
SlurmdLogFile=/var/log/slurm/slurmd.log
$(slurmd -C | head -1) State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF

# A key for munge if the package made none; then the daemons.
[ -s /etc/munge/munge.key ] || mungekey --create --force >/dev/null 2>&1 || dd if=/dev/urandom of=/etc/munge/munge.key bs=1024 count=1 2>/dev/null
chown -R munge: /etc/munge /run/munge /var/lib/munge /var/log/munge 2>/dev/null || true
chmod 400 /etc/munge/munge.key
pkill -x slurmd 2>/dev/null || true
pkill -x slurmctld 2>/dev/null || true
pgrep -x munged >/dev/null || runuser -u munge -- /usr/sbin/munged
stop() {
    pkill -x slurmd 2>/dev/null || true
    pkill -x slurmctld 2>/dev/null || true
}
trap stop EXIT
slurmctld -c
slurmd
for _ in $(seq 60); do
    sinfo -h -o %T 2>/dev/null | grep -qE '^(idle|mixed)' && break
    scontrol update nodename="$host" state=resume 2>/dev/null || true
    sleep 1
done
sinfo

cd "$work"
# Each task computes one shard of the members on one node.
array=$(sbatch --parsable --array=0-3 --output=shard_%a.log \
    --wrap "'$ensemble' --members $members --threads 1 --shard \$SLURM_ARRAY_TASK_ID/4 --out shard\$SLURM_ARRAY_TASK_ID.csv")
# The merge runs once every task has succeeded.
merge=$(sbatch --parsable --wait --dependency=afterok:"$array" --output=merge.log \
    --wrap "'$ensemble' merge --members $members --out merged.csv shard0.csv shard1.csv shard2.csv shard3.csv")
echo "array job $array, merge job $merge"
cat merge.log
"$ensemble" --members "$members" --threads 1 --out unsharded.csv >/dev/null
if cmp merged.csv unsharded.csv; then
    echo "the merged shards equal the unsharded run, byte for byte ($members members)"
else
    echo "the merged shards differ from the unsharded run" >&2
    exit 1
fi
