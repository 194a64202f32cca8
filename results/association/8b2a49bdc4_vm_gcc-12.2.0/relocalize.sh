cd /work/wt/assoc
first=1
for world in uniform rooms; do
for n in 100 1000 10000; do
  for m in 5 10 20; do
    if [ $first = 1 ]; then ./build/bin/arbor relocalize --world $world --landmarks $n --observations $m --clutter 2 --trials 50 --csv; first=0;
    else ./build/bin/arbor relocalize --world $world --landmarks $n --observations $m --clutter 2 --trials 50 --csv | tail -n +2; fi
  done
done
done
