PM-PHOTONS
version=1
endian=little
record_size=20
kdtree=0
count=0
emitted=1
bbox=0 0 0 0 0 0
light_hash=00000000000000aa
time=0
seeds=1
command=mkphotons -n 0 -o /work/main/tests/fuzz/corpus/photons/empty.pm

