//! The GeoTIFF reader ([`read_geotiff`], [`parse_geotiff`]) against bad files: each refusal
//! names the file and the tag or value at fault; and a mutational fuzzer
//! (seeded: byte flips, a field of the directory set to a value that
//! breaks careless readers, the georeferencing's numbers made NaN,
//! infinite, zero or negative, truncation, bytes inserted) on GeoTIFF
//! files of every kind the reader takes: no case panics, and none takes
//! more memory than its bound.

use std::io::Cursor;
use std::path::{Path, PathBuf};

use crate::grid_fuzzer::catch_panic;
use dismech::error::DismechError;
use dismech::grid::{
    parse_geotiff, read_geotiff, write_geotiff, FileKind, GeoTiffProblem, GridCellProblem,
    GridError, MissingTags, Raster, TiffDamage, MAX_GEOTIFF_EXPANSION, MAX_GRID_CELLS,
};
use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};
use tiff::encoder::colortype::{Gray16, Gray32Float, Gray64Float, GrayI16, RGB8};
use tiff::encoder::compression::DeflateLevel;
use tiff::encoder::{colortype::ColorType, Compression, TiffEncoder, TiffValue};
use tiff::tags::Tag;

/// A folder for a test's files, emptied.
fn folder(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("geotiff_input_{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The GeoTIFF tags of a file: pixel scale, tie point, GeoKeys (with the
/// raster type `raster_type`) and no-data text, each optional.
#[derive(Clone)]
struct Tags {
    scale: Option<Vec<f64>>,
    tie: Option<Vec<f64>>,
    raster_type: Option<u16>,
    nodata: Option<&'static str>,
}

impl Tags {
    fn good() -> Self {
        Tags {
            scale: Some(vec![2.0, 2.0, 0.0]),
            tie: Some(vec![0.0, 0.0, 0.0, 1000.0, 2010.0, 0.0]),
            raster_type: Some(1),
            nodata: Some("-9999"),
        }
    }
}

/// A TIFF of `columns × rows` samples `data` of colour type `C`,
/// compressed with `compression`, with `tags`.
fn tiff_file<C: ColorType>(
    columns: u32,
    rows: u32,
    data: &[C::Inner],
    compression: Compression,
    tags: &Tags,
) -> Vec<u8>
where
    [C::Inner]: TiffValue,
{
    let mut bytes = Cursor::new(Vec::new());
    let mut tiff = TiffEncoder::new(&mut bytes)
        .unwrap()
        .with_compression(compression);
    let mut image = tiff.new_image::<C>(columns, rows).unwrap();
    let dir = image.encoder();
    if let Some(scale) = &tags.scale {
        dir.write_tag(Tag::ModelPixelScaleTag, &scale[..]).unwrap();
    }
    if let Some(tie) = &tags.tie {
        dir.write_tag(Tag::ModelTiepointTag, &tie[..]).unwrap();
    }
    if let Some(t) = tags.raster_type {
        dir.write_tag(Tag::GeoKeyDirectoryTag, &[1u16, 1, 0, 1, 1025, 0, 1, t][..])
            .unwrap();
    }
    if let Some(nodata) = tags.nodata {
        dir.write_tag(Tag::GdalNodata, nodata).unwrap();
    }
    image.write_data(data).unwrap();
    bytes.into_inner()
}

/// A 6 × 4 grid of heights with a cell of no data.
fn heights() -> Vec<f64> {
    (0..24)
        .map(|k| {
            if k == 7 {
                -9999.0
            } else {
                100.0 + 0.25 * k as f64
            }
        })
        .collect()
}

/// The seeds of the fuzzer: files the reader takes, of every kind.
fn seeds(name: &str) -> Vec<Vec<u8>> {
    let dir = folder(name);
    let raster = Raster::from_fn(9, 7, 350_000.0, 4_500_000.0, 5.0, |x, y| {
        (x < 350_040.0).then_some(0.1 * (x - 350_000.0) + 0.3 * (y - 4_500_000.0))
    })
    .unwrap();
    let written = dir.join("written.tif");
    write_geotiff(&written, &raster).unwrap();
    let h = heights();
    let h32: Vec<f32> = h.iter().map(|&v| v as f32).collect();
    let h16: Vec<i16> = h.iter().map(|&v| v as i16).collect();
    let u16s: Vec<u16> = h.iter().map(|&v| v.max(0.0) as u16).collect();
    let point = Tags {
        raster_type: Some(2),
        ..Tags::good()
    };
    vec![
        std::fs::read(&written).unwrap(),
        tiff_file::<Gray64Float>(6, 4, &h, Compression::Lzw, &Tags::good()),
        tiff_file::<Gray32Float>(6, 4, &h32, Compression::Deflate(DeflateLevel::Fast), &point),
        tiff_file::<GrayI16>(6, 4, &h16, Compression::Lzw, &Tags::good()),
        tiff_file::<Gray16>(
            6,
            4,
            &u16s,
            Compression::Uncompressed,
            &Tags {
                nodata: Some("0"),
                ..Tags::good()
            },
        ),
    ]
}

fn kind(e: &DismechError) -> &'static str {
    match e {
        DismechError::Grid(GridError::GeoTiff { .. }) => "GeoTiff",
        DismechError::Grid(GridError::TooLarge { .. }) => "GridTooLarge",
        DismechError::Grid(GridError::Cell { .. }) => "GridCell",
        DismechError::InvalidParameter { .. } => "InvalidParameter",
        _ => "other",
    }
}

#[test]
fn every_seed_reads_with_its_grid() {
    let dir = folder("seed_reads");
    for (k, bytes) in seeds("seeds_read").iter().enumerate() {
        let path = dir.join(format!("seed{k}.tif"));
        std::fs::write(&path, bytes).unwrap();
        let r = read_geotiff(&path).unwrap_or_else(|e| panic!("seed {k}: {e}"));
        if k == 0 {
            assert_eq!(r.lower_left(), (350_000.0, 4_500_000.0));
            continue;
        }
        assert_eq!((r.columns(), r.rows(), r.cell_size()), (6, 4, 2.0));
        // The tie point is the upper-left corner (y 2010, 4 rows of 2 m),
        // or with pixels as points the first cell's centre.
        let expected = if k == 2 {
            (999.0, 2003.0)
        } else {
            (1000.0, 2002.0)
        };
        assert_eq!(r.lower_left(), expected, "seed {k}");
        assert_eq!(r.get(1, 1), None, "seed {k}");
        // 100.5, or 100 in the integer files.
        let expected = if k >= 3 { 100.0 } else { 100.5 };
        assert_eq!(r.get(0, 2), Some(expected), "seed {k}");
    }
}

#[test]
fn bad_geotiffs_are_refused_naming_the_file_and_the_tag() {
    let dir = folder("bad");
    let h = heights();
    let refuse = |name: &str, bytes: Vec<u8>| -> DismechError {
        let path = dir.join(name);
        std::fs::write(&path, bytes).unwrap();
        let e = read_geotiff(&path).unwrap_err();
        assert!(e.to_string().contains(name), "{e}");
        e
    };
    let with = |tags: Tags| tiff_file::<Gray64Float>(6, 4, &h, Compression::Uncompressed, &tags);
    let message = |e: DismechError| e.to_string();

    let e = message(refuse("text.tif", b"ncols 2\nnrows 2\n".to_vec()));
    assert!(e.contains("not a TIFF file"), "{e}");
    let e = message(refuse("empty.tif", Vec::new()));
    assert!(e.contains("not a TIFF file"), "{e}");
    let e = message(refuse(
        "no_scale.tif",
        with(Tags {
            scale: None,
            ..Tags::good()
        }),
    ));
    assert!(e.contains("has no ModelPixelScale (33550)"), "{e}");
    let e = message(refuse(
        "no_tie.tif",
        with(Tags {
            tie: None,
            ..Tags::good()
        }),
    ));
    assert!(e.contains("has no ModelTiepoint (33922)"), "{e}");
    let e = message(refuse(
        "nan_scale.tif",
        with(Tags {
            scale: Some(vec![f64::NAN, 2.0, 0.0]),
            ..Tags::good()
        }),
    ));
    assert!(e.contains("ModelPixelScale (33550) = (NaN, 2)"), "{e}");
    let e = message(refuse(
        "zero_scale.tif",
        with(Tags {
            scale: Some(vec![0.0, 0.0, 0.0]),
            ..Tags::good()
        }),
    ));
    assert!(e.contains("finite and positive"), "{e}");
    let e = message(refuse(
        "two_ties.tif",
        with(Tags {
            tie: Some(vec![0.0; 12]),
            ..Tags::good()
        }),
    ));
    assert!(e.contains("ModelTiepoint (33922) has 12 values"), "{e}");
    let e = message(refuse(
        "raster_type.tif",
        with(Tags {
            raster_type: Some(3),
            ..Tags::good()
        }),
    ));
    assert!(e.contains("GTRasterTypeGeoKey (1025) = 3"), "{e}");
    let e = message(refuse(
        "nodata.tif",
        with(Tags {
            nodata: Some("none"),
            ..Tags::good()
        }),
    ));
    assert!(e.contains("GDAL_NODATA (42113) = `none`"), "{e}");
    let e = refuse(
        "infinite_tie.tif",
        with(Tags {
            tie: Some(vec![0.0, 0.0, 0.0, f64::INFINITY, 0.0, 0.0]),
            ..Tags::good()
        }),
    );
    assert!(
        e.to_string()
            .contains("invalid raster x of the lower-left corner = inf"),
        "{e}"
    );
    let mut infinite = h.clone();
    infinite[9] = f64::INFINITY;
    let e = refuse(
        "infinite.tif",
        tiff_file::<Gray64Float>(6, 4, &infinite, Compression::Uncompressed, &Tags::good()),
    );
    assert!(
        matches!(
            e,
            DismechError::Grid(GridError::Cell {
                row: 1,
                column: 3,
                ..
            })
        ),
        "{e}"
    );
    let rgb = vec![0u8; 6 * 4 * 3];
    let e = message(refuse(
        "rgb.tif",
        tiff_file::<RGB8>(6, 4, &rgb, Compression::Uncompressed, &Tags::good()),
    ));
    assert!(e.contains("RGB(8)") && e.contains("one band"), "{e}");
    // Truncated: the values are not all there.
    let mut cut = with(Tags::good());
    cut.truncate(150);
    let e = message(refuse("cut.tif", cut));
    assert!(e.contains("cut.tif"), "{e}");
    // Not a regular file.
    let e = read_geotiff(&dir).unwrap_err().to_string();
    assert!(e.contains("a directory, not a regular file"), "{e}");
    let e = read_geotiff(&dir.join("missing.tif"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("missing.tif: cannot read the file"), "{e}");
}

#[test]
fn geotiff_refusals_carry_a_typed_cause() {
    let dir = folder("typed");
    let h = heights();
    let problem = |name: &str, bytes: Vec<u8>| -> GeoTiffProblem {
        match parse_geotiff(&bytes, name).unwrap_err() {
            DismechError::Grid(GridError::GeoTiff { file, problem }) => {
                assert_eq!(file, name);
                problem
            }
            e => panic!("{e}"),
        }
    };
    let with = |tags: Tags| tiff_file::<Gray64Float>(6, 4, &h, Compression::Uncompressed, &tags);

    let start = [b'n', b'c'];
    let damage = TiffDamage::ByteOrder { start };
    assert_eq!(
        problem("text.tif", b"ncols 2\nnrows 2\n".to_vec()),
        GeoTiffProblem::Unreadable { damage }
    );
    let version = b"II\x29\x00\x08\x00\x00\x00".to_vec();
    let damage = TiffDamage::Version { version: 41 };
    assert_eq!(
        problem("v41.tif", version),
        GeoTiffProblem::Unreadable { damage }
    );
    assert!(matches!(
        problem("empty.tif", Vec::new()),
        GeoTiffProblem::Unreadable {
            damage: TiffDamage::ShortRead {
                bytes: 8,
                offset: 0,
                size: 0,
                ..
            }
        }
    ));
    let no_scale = with(Tags {
        scale: None,
        ..Tags::good()
    });
    let missing = MissingTags::Scale;
    assert_eq!(
        problem("no_scale.tif", no_scale),
        GeoTiffProblem::NotGeoreferenced { missing }
    );
    let no_tie = with(Tags {
        tie: None,
        ..Tags::good()
    });
    let missing = MissingTags::Tiepoint;
    assert_eq!(
        problem("no_tie.tif", no_tie),
        GeoTiffProblem::NotGeoreferenced { missing }
    );
    let zero = with(Tags {
        scale: Some(vec![0.0, 0.0, 0.0]),
        ..Tags::good()
    });
    assert_eq!(
        problem("zero_scale.tif", zero),
        GeoTiffProblem::ScaleNotPositive { x: 0.0, y: 0.0 }
    );
    let oblong = with(Tags {
        scale: Some(vec![2.0, 3.0, 0.0]),
        ..Tags::good()
    });
    assert_eq!(
        problem("oblong.tif", oblong),
        GeoTiffProblem::CellsNotSquare { x: 2.0, y: 3.0 }
    );
    let two_ties = with(Tags {
        tie: Some(vec![0.0; 12]),
        ..Tags::good()
    });
    assert_eq!(
        problem("two_ties.tif", two_ties),
        GeoTiffProblem::TiepointCount { values: 12 }
    );
    let raster_type = with(Tags {
        raster_type: Some(3),
        ..Tags::good()
    });
    assert_eq!(
        problem("raster_type.tif", raster_type),
        GeoTiffProblem::RasterType {
            value: 3,
            location: 0
        }
    );
    let nodata = with(Tags {
        nodata: Some("none"),
        ..Tags::good()
    });
    let text = "none".to_string();
    assert_eq!(
        problem("nodata.tif", nodata),
        GeoTiffProblem::NodataNotNumber { text }
    );
    let infinite_tie = with(Tags {
        tie: Some(vec![0.0, 0.0, 0.0, f64::INFINITY, 0.0, 0.0]),
        ..Tags::good()
    });
    match problem("infinite_tie.tif", infinite_tie) {
        GeoTiffProblem::Georeference {
            error,
            width: 6,
            height: 4,
            ..
        } => assert!(
            matches!(*error, DismechError::InvalidParameter { value, .. } if value.is_infinite()),
            "{error}"
        ),
        p => panic!("{p}"),
    }
    let rgb = vec![0u8; 6 * 4 * 3];
    let rgb = tiff_file::<RGB8>(6, 4, &rgb, Compression::Uncompressed, &Tags::good());
    match problem("rgb.tif", rgb) {
        GeoTiffProblem::NotOneBand { color } => assert_eq!(color, "RGB(8)"),
        p => panic!("{p}"),
    }
    let mut infinite = h.clone();
    infinite[9] = f64::INFINITY;
    let infinite =
        tiff_file::<Gray64Float>(6, 4, &infinite, Compression::Uncompressed, &Tags::good());
    assert_eq!(
        parse_geotiff(&infinite, "infinite.tif").unwrap_err(),
        DismechError::Grid(GridError::Cell {
            file: "infinite.tif".into(),
            row: 1,
            column: 3,
            problem: GridCellProblem::NotFinite {
                value: f64::INFINITY
            },
        })
    );
    match read_geotiff(&dir).unwrap_err() {
        DismechError::Grid(GridError::GeoTiff { problem, .. }) => assert_eq!(
            problem,
            GeoTiffProblem::NotRegularFile {
                kind: FileKind::Directory
            }
        ),
        e => panic!("{e}"),
    }
    match read_geotiff(&dir.join("missing.tif")).unwrap_err() {
        DismechError::Grid(GridError::GeoTiff {
            problem: GeoTiffProblem::CannotRead { kind, .. },
            ..
        }) => assert_eq!(kind, std::io::ErrorKind::NotFound),
        e => panic!("{e}"),
    }
}

#[test]
fn a_file_claiming_more_cells_than_the_cap_is_refused_before_decoding() {
    let dir = folder("huge");
    // A one-row image whose width field is set to 2^31 after writing:
    // 2^31 cells > 10^8.
    let mut bytes = tiff_file::<Gray64Float>(
        6,
        1,
        &heights()[..6],
        Compression::Uncompressed,
        &Tags::good(),
    );
    set_field(&mut bytes, 256, 1 << 31);
    let path = dir.join("wide.tif");
    std::fs::write(&path, &bytes).unwrap();
    let e = read_geotiff(&path).unwrap_err();
    assert!(
        matches!(e, DismechError::Grid(GridError::TooLarge { columns: 2147483648, rows: 1, cap, .. }) if cap == MAX_GRID_CELLS),
        "{e}"
    );
    // 10^7 cells claimed by an uncompressed file of a few hundred bytes.
    set_field(&mut bytes, 256, 10_000_000);
    std::fs::write(&path, &bytes).unwrap();
    let e = read_geotiff(&path).unwrap_err();
    assert!(
        matches!(
            &e,
            DismechError::Grid(GridError::GeoTiff {
                problem: GeoTiffProblem::ValuesExceedFile {
                    width: 10_000_000,
                    height: 1,
                    bits: 64,
                    compression: 1,
                    ..
                },
                ..
            })
        ),
        "{e}"
    );
    let e = e.to_string();
    assert!(e.contains("cannot be held in a file of"), "{e}");
}

/// Set the value of the entry of `tag` in the first directory of a
/// little-endian TIFF (a SHORT or LONG held in the entry).
fn set_field(bytes: &mut [u8], tag: u16, value: u32) {
    let ifd = u32::from_le_bytes(bytes[4..8].try_into().unwrap()) as usize;
    let count = u16::from_le_bytes(bytes[ifd..ifd + 2].try_into().unwrap()) as usize;
    for k in 0..count {
        let entry = ifd + 2 + 12 * k;
        if u16::from_le_bytes(bytes[entry..entry + 2].try_into().unwrap()) == tag {
            // As a LONG, so that any value fits.
            bytes[entry + 2..entry + 4].copy_from_slice(&4u16.to_le_bytes());
            bytes[entry + 8..entry + 12].copy_from_slice(&value.to_le_bytes());
            return;
        }
    }
    panic!("no tag {tag}");
}

/// Values that break careless readers, for a field of 4 bytes.
const NASTY: [u32; 10] = [
    0,
    1,
    2,
    0xFFFF,
    0x1_0000,
    0x7FFF_FFFF,
    0x8000_0000,
    0xFFFF_FFFF,
    100_000_000,
    100_000_001,
];

/// One mutation of `seed`.
fn mutate(rng: &mut StdRng, seed: &[u8]) -> Vec<u8> {
    let mut bytes = seed.to_vec();
    let rounds = rng.random_range(1..=3);
    for _ in 0..rounds {
        if bytes.len() < 16 {
            break;
        }
        let len = bytes.len();
        match rng.random_range(0..7) {
            // Flip bytes.
            0 => {
                for _ in 0..rng.random_range(1..=8) {
                    let at = rng.random_range(0..len);
                    bytes[at] = rng.random_range(0..=255);
                }
            }
            // A field of a directory entry (tag, type, count or value).
            1 | 2 => {
                let ifd = u32::from_le_bytes(bytes[4..8].try_into().unwrap()) as usize;
                let count = bytes
                    .get(ifd..ifd + 2)
                    .map_or(0, |b| u16::from_le_bytes(b.try_into().unwrap()) as usize);
                if count == 0 {
                    continue;
                }
                let entry = ifd + 2 + 12 * rng.random_range(0..count);
                let (offset, width) = [(0, 2), (2, 2), (4, 4), (8, 4)][rng.random_range(0..4)];
                let value =
                    NASTY[rng.random_range(0..NASTY.len())].wrapping_add(rng.random_range(0..3));
                if let Some(field) = bytes.get_mut(entry + offset..entry + offset + width) {
                    field.copy_from_slice(&value.to_le_bytes()[..width]);
                }
            }
            // An 8-byte number (a scale, a tie point, a value) made nasty.
            3 => {
                let at = rng.random_range(0..len - 8);
                let v = [
                    f64::NAN,
                    f64::INFINITY,
                    -1.0,
                    0.0,
                    1e308,
                    -1e308,
                    5e-324,
                    -9999.0,
                ][rng.random_range(0..8)];
                bytes[at..at + 8].copy_from_slice(&v.to_le_bytes());
            }
            // Truncate.
            4 => bytes.truncate(rng.random_range(0..len)),
            // Insert bytes.
            5 => {
                let at = rng.random_range(0..len);
                let n = rng.random_range(1..16);
                let fill = rng.random_range(0..=255u8);
                bytes.splice(at..at, std::iter::repeat_n(fill, n));
            }
            // The header's directory offset.
            _ => {
                let value = NASTY[rng.random_range(0..NASTY.len())];
                bytes[4..8].copy_from_slice(&value.to_le_bytes());
            }
        }
    }
    bytes
}

/// The most memory a case may hold at once: what the decoder may be
/// asked to allocate for the values ([`MAX_GEOTIFF_EXPANSION`] bytes per
/// byte of a compressed file), twice (the decoded samples and the
/// raster's values), plus 4 MiB for the directory's values (the decoder
/// reads a tag's values up to 1 MiB) and buffers.
fn memory_bound(input: usize) -> u64 {
    2 * MAX_GEOTIFF_EXPANSION * input as u64 + 4 * 1024 * 1024
}

#[test]
fn fuzzed_geotiffs_never_panic_nor_outgrow_their_memory_bound() {
    // 100 000 cases in `cargo test` (a fraction of a second);
    // DISMECH_GEOTIFF_FUZZ=SEED,CASES runs another seed or more cases.
    let (seed, cases) = std::env::var("DISMECH_GEOTIFF_FUZZ").map_or((31, 100_000), |v| {
        let (s, c) = v.split_once(',').expect("DISMECH_GEOTIFF_FUZZ=SEED,CASES");
        (s.parse().unwrap(), c.parse().unwrap())
    });
    const NAME: &str = "case.tif";
    let seeds = seeds("seeds_fuzzed");
    let mut rng = StdRng::seed_from_u64(seed);
    let (mut accepted, mut panics, mut largest_ratio) = (0u64, Vec::new(), 0.0f64);
    let mut over_bound = Vec::new();
    let mut unnamed = Vec::new();
    let mut refused = std::collections::BTreeMap::<&str, u64>::new();
    for index in 0..cases {
        let seed = &seeds[rng.random_range(0..seeds.len())];
        let bytes = mutate(&mut rng, seed);
        let mut outcome = None;
        // A panic's message is recorded, not printed: the other tests of
        // this binary, running beside it, keep theirs.
        let info = allocation_counter::measure(|| {
            outcome = Some(catch_panic(|| parse_geotiff(&bytes, NAME)));
        });
        largest_ratio = largest_ratio.max(info.bytes_max as f64 / bytes.len().max(1) as f64);
        if info.bytes_max > memory_bound(bytes.len()) {
            over_bound.push((index, info.bytes_max, bytes.len()));
        }
        match outcome.unwrap() {
            Ok(Ok(_)) => accepted += 1,
            Ok(Err(e)) => {
                if !e.to_string().contains(NAME) {
                    unnamed.push((index, e.to_string()));
                }
                *refused.entry(kind(&e)).or_default() += 1;
            }
            Err(message) => panics.push((index, message)),
        }
    }
    eprintln!(
        "{cases} cases (seed {seed}): {accepted} accepted, refused {refused:?}, {} panics, largest peak {largest_ratio:.0} bytes per byte of file",
        panics.len()
    );
    assert!(panics.is_empty(), "cases that panicked: {panics:?}");
    assert!(
        over_bound.is_empty(),
        "cases over their memory bound (case, peak bytes, file bytes): {over_bound:?}"
    );
    assert!(
        unnamed.is_empty(),
        "refusals not naming the file: {unnamed:?}"
    );
    assert!(!refused.contains_key("other"), "{refused:?}");
    // The run reaches both sides: files accepted and refused.
    assert!(accepted >= cases / 20, "{accepted} accepted");
    assert!(refused["GeoTiff"] >= cases / 4, "{refused:?}");
}
