# lib_study.sh: the small two-scene study that the spread tests render, sourced by
# tests/e2e_queue_study.sh (a queue's workers) and ci/slurm/test-local.sh (a Slurm array).
# small_study NAME ROOT SEEDS SAMPLERS: its YAML on stdout: ROOT's checker and cornell scenes at
# 10x8, one process, light threshold 50, a jitter reference at threshold 10, thresholds 50 and 25,
# seeds SEEDS ("1, 2, 3"), one variant per sampler in SAMPLERS ("jitter random").
small_study() {
    printf 'name: %s\nscenes: [%s/scenes/checker.yaml, %s/scenes/cornell.yaml]\n' "$1" "$2" "$2"
    printf 'width: 10\nheight: 8\nprocesses: 1\nlight_threshold: 50\n'
    printf 'reference: { sampler: jitter, threshold: 10 }\nseeds: [%s]\nsweep: { threshold: [50, 25] }\nvariants:\n' "$3"
    for sampler in $4; do printf '  - { sampler: %s }\n' "$sampler"; done
}
