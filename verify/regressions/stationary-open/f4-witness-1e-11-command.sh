target/release/verify oracle /tmp/stationary_failures/f4-witness-1e-11/profile.toml pawn --eps 1e-3 --pose-b '{"translation":[0.8329134106710407,1.7396780584121636,-0.7616803075236778],"rotation":[0.2358550308816224,0.07178127343805382,-0.530607166160348,0.8109721871992438]}'
STATIONARY_CASE="101794 4 3" cargo test --release -p verify --test proptest_stationary replay
