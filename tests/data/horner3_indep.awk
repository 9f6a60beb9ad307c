# horner3_indep.awk - horner3 stimuli independent of any shadesim generator:
# each coefficient a..d uniform over the range it spans in the vector file
# given (vectors/horner3.vec), t uniform in [0, 1), the cubic in double as
# the expected output. awk -v n=N -v seed=S -f tests/data/horner3_indep.awk vectors/horner3.vec
!/^#/ { for (j = 1; j <= 4; j++) { if (!seen || $j < lo[j]) lo[j] = $j; if (!seen || $j > hi[j]) hi[j] = $j } seen = 1 }
END {
    srand(seed ? seed : 31)
    if (!n) n = 20000
    print "# shadesim vectors 1\n# unit: horner3\n# inputs: a b c d t\n# outputs: y"
    for (k = 0; k < n; k++) {
        for (j = 1; j <= 4; j++) v[j] = lo[j] + (hi[j] - lo[j]) * rand()
        t = rand()
        printf "%.17g %.17g %.17g %.17g %.17g | %.17g\n", v[1], v[2], v[3], v[4], t, ((v[1] * t + v[2]) * t + v[3]) * t + v[4]
    }
}
