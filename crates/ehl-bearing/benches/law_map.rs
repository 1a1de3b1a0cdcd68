//! Reading the law maps: all embedded map files parsed from their compact binary form (what the
//! library embeds) against the same maps parsed from JSON text (what `law-map assemble` writes
//! for a `.json` file), side by side in one run. The first query of the `map` method that
//! reaches a map pays its parse once (docs/law_map.md §5). And one query of the first embedded map
//! (17 × 5 × 9 tensor nodes) against its sparse subsets of levels 5 and 9 (the full level, the
//! same interpolant by the combination technique), at the same 64 points. And one query of each
//! harmonic map: the seed oil's (4 groups, 11 × 5 × 9 × 3 tensor nodes) and the mineral oils'
//! (6 groups, a sparse map of level 5, 2385 nodes), 64 points of each.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use ehl_bearing::law_map::LawMap;

fn parse(c: &mut Criterion) {
    let maps = LawMap::embedded_maps();
    let binary: Vec<Vec<u8>> = maps.iter().map(|m| m.to_binary()).collect();
    let json: Vec<String> = maps.iter().map(|m| m.to_json()).collect();
    let mut g = c.benchmark_group("law_map_parse_all_embedded");
    g.sample_size(20);
    g.bench_function("binary", |b| {
        b.iter(|| {
            for bytes in &binary {
                black_box(LawMap::from_binary(black_box(bytes)).unwrap());
            }
        })
    });
    g.bench_function("json", |b| {
        b.iter(|| {
            for text in &json {
                black_box(LawMap::from_json(black_box(text)).unwrap());
            }
        })
    });
    g.finish();
    // The first map alone (the seed oil's; a seed-case query parses only it).
    let mut g = c.benchmark_group("law_map_parse_first");
    g.bench_function("binary", |b| {
        b.iter(|| black_box(LawMap::from_binary(black_box(&binary[0])).unwrap()))
    });
    g.bench_function("json", |b| {
        b.iter(|| black_box(LawMap::from_json(black_box(&json[0])).unwrap()))
    });
    g.finish();
}

fn query(c: &mut Criterion) {
    let tensor = LawMap::embedded();
    let points: Vec<_> = ehl_bearing::study::held_out_points(&tensor.spec, 64, 11)
        .into_iter()
        .map(|(g, _)| g)
        .collect();
    let mut g = c.benchmark_group("law_map_query_64_points");
    let mut run = |name: &str, map: &LawMap| {
        g.bench_function(name, |b| {
            b.iter(|| {
                for p in &points {
                    black_box(map.query(black_box(p)).unwrap());
                }
            })
        });
    };
    run("tensor_765_nodes", tensor);
    run(
        "sparse_level_5_261_nodes",
        &tensor.sparse_subset(5).unwrap(),
    );
    run(
        "sparse_level_9_765_nodes",
        &tensor.sparse_subset(9).unwrap(),
    );
    g.finish();
    let mut g = c.benchmark_group("law_map_harmonic_query_64_points");
    for (name, map) in [
        ("seed_oil_tensor_1485_nodes", "seed_oil_harmonic"),
        (
            "mineral_oils_sparse_level_5_2385_nodes",
            "mineral_oils_harmonic",
        ),
        (
            "mineral_oils_lightest_sparse_level_4_993_nodes",
            "mineral_oils_lightest_harmonic",
        ),
    ] {
        let map = LawMap::embedded_named(map).unwrap();
        let points: Vec<_> = ehl_bearing::study::held_out_points(&map.spec, 64, 11)
            .into_iter()
            .map(|(g, psi_h)| (g, psi_h.unwrap()))
            .collect();
        g.bench_function(name, |b| {
            b.iter(|| {
                for (p, psi_h) in &points {
                    black_box(map.query_harmonic(black_box(p), *psi_h).unwrap());
                }
            })
        });
    }
    g.finish();
}

criterion_group!(benches, parse, query);
criterion_main!(benches);
