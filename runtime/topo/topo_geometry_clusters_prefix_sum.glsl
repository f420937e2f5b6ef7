// prefix_sum(lid, n, total): the exclusive prefix sum of n over a
// workgroup of THREADS invocations (Hillis-Steele, double-buffered in
// shared sums[2 THREADS]), and the total.
shared uint sums[2u * THREADS];
uint prefix_sum(uint lid, uint n, out uint total) {
    uint from = 0u;
    sums[lid] = n;
    memoryBarrierShared();
    barrier();
    for (uint offset = 1u; offset < THREADS; offset <<= 1u) {
        uint v = sums[from + lid];
        if (lid >= offset)
            v += sums[from + lid - offset];
        sums[THREADS - from + lid] = v;
        from = THREADS - from;
        memoryBarrierShared();
        barrier();
    }
    total = sums[from + THREADS - 1u];
    return sums[from + lid] - n;
}
