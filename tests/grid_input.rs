//! Grid files whose header asks for absurd sizes or values: each is refused
//! with a typed error naming the file, the key and the value, before any
//! memory is sized by it; the slope-grid loader returns the error instead
//! of indexing out of bounds.

use dismech::error::DismechError;
use dismech::grid::{
    parse_esri_ascii, GridError, GridFormatProblem, GridHeaderProblem, Raster, MAX_GRID_CELLS,
};
use dismech::hpm::SlopeGrids;

/// A header with `ncols` and `nrows` as given and `values` as data.
fn grid(ncols: &str, nrows: &str, values: &str) -> String {
    format!(
        "ncols {ncols}\nnrows {nrows}\nxllcorner 0\nyllcorner 0\ncellsize 10\nNODATA_value -9999\n{values}\n"
    )
}

/// One row of 24 values, as in the shipped grids.
fn row_of_24() -> String {
    (0..24)
        .map(|k| format!("{}", 70.0 + k as f64))
        .collect::<Vec<_>>()
        .join(" ")
}

/// The most memory reading a text may take: 64 bytes per byte of text plus
/// 64 KiB (the bound of the grid fuzzer, `tests/grid_fuzzer`).
fn memory_bound(text: &str) -> u64 {
    64 * text.len() as u64 + 64 * 1024
}

#[test]
fn nrows_2147483648_in_a_seven_line_file_is_refused_before_any_allocation() {
    // Used to abort the process: "memory allocation of 824633720832 bytes
    // failed" (24 × 2^31 cells of 16 bytes, reserved from the header).
    let text = grid("24", "2147483648", &row_of_24());
    assert_eq!(text.lines().count(), 7);
    let mut result = None;
    let memory = allocation_counter::measure(|| {
        result = Some(parse_esri_ascii(&text, "ground.asc"));
    });
    match result.expect("parsed").unwrap_err() {
        DismechError::Grid(GridError::TooLarge {
            file,
            columns,
            rows,
            cells,
            cap,
        }) => {
            assert_eq!(file, "ground.asc");
            assert_eq!((columns, rows), (24, 2_147_483_648));
            assert_eq!(cells, 24 * 2_147_483_648);
            assert_eq!(cap, MAX_GRID_CELLS);
        }
        e => panic!("{e}"),
    }
    assert!(
        memory.bytes_max <= memory_bound(&text),
        "reading {} bytes took {} bytes at once",
        text.len(),
        memory.bytes_max
    );
}

#[test]
fn ncols_1e30_is_refused_as_not_a_whole_number() {
    // Used to panic with "capacity overflow" (1e30 as usize saturates).
    let text = grid("1e30", "1", "1");
    match parse_esri_ascii(&text, "ground.asc").unwrap_err() {
        DismechError::Grid(GridError::Header {
            file,
            line,
            key,
            value,
            ..
        }) => assert_eq!(
            (file.as_str(), line, key.as_str(), value.as_str()),
            ("ground.asc", 1, "ncols", "1e30")
        ),
        e => panic!("{e}"),
    }
}

#[test]
fn ncols_274177_nrows_67280421310721_is_refused_not_wrapped_to_one_cell() {
    // 274177 × 67280421310721 = 2^64 + 1: the unchecked product wrapped to
    // 1 cell and the one-value file was accepted.
    let text = grid("274177", "67280421310721", "1");
    let exact = 274_177_u128 * 67_280_421_310_721_u128;
    assert_eq!(exact, u128::from(u64::MAX) + 2);
    match parse_esri_ascii(&text, "slip.asc").unwrap_err() {
        DismechError::Grid(GridError::TooLarge {
            file, rows, cells, ..
        }) => {
            assert_eq!(
                (file.as_str(), rows, cells),
                ("slip.asc", 67_280_421_310_721, exact)
            );
        }
        e => panic!("{e}"),
    }
}

#[test]
fn slope_grids_read_of_ncols_274177_nrows_67280421310721_returns_an_error() {
    // Two such files (ground and slip surface on the same wrapped grid) used
    // to be accepted, and the loader then panicked out of bounds in
    // `Raster::get` as it walked the 274177 columns of a 1-value grid.
    let dir = std::env::temp_dir().join(format!("dismech-grid-input-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let ground = dir.join("ground.asc");
    std::fs::write(&ground, grid("274177", "67280421310721", "100")).unwrap();
    let slip = dir.join("slip.asc");
    std::fs::write(&slip, grid("274177", "67280421310721", "90")).unwrap();
    let result = std::panic::catch_unwind(|| SlopeGrids::read(&ground, &slip, None));
    std::fs::remove_dir_all(&dir).unwrap();
    match result.expect("no panic") {
        Err(DismechError::Grid(GridError::TooLarge { file, .. })) => {
            assert_eq!(file, ground.display().to_string())
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn ncols_beyond_64_bits_is_refused_not_saturated() {
    // 18446744073709551616 = 2^64 used to become usize::MAX cells and panic
    // with "capacity overflow".
    let text = grid("18446744073709551616", "1", "1");
    match parse_esri_ascii(&text, "ground.asc").unwrap_err() {
        DismechError::Grid(GridError::Header { key, value, .. }) => {
            assert_eq!(
                (key.as_str(), value.as_str()),
                ("ncols", "18446744073709551616")
            )
        }
        e => panic!("{e}"),
    }
}

#[test]
fn a_corner_or_cell_size_reaching_past_the_largest_coordinate_is_refused() {
    // yllcorner 1e308 with 3 cells of 1e308: the top edge was infinite and
    // the grid accepted.
    let text = "ncols 1\nnrows 3\nxllcorner 0\nyllcorner 1e308\ncellsize 1e308\n1 2 3\n";
    match parse_esri_ascii(text, "water.asc").unwrap_err() {
        DismechError::Grid(GridError::Header {
            file,
            line,
            key,
            value,
            ..
        }) => assert_eq!(
            (file.as_str(), line, key.as_str(), value.as_str()),
            ("water.asc", 4, "yllcorner", "1e308")
        ),
        e => panic!("{e}"),
    }
    // An infinite corner was refused without the file's name.
    let text = "ncols 1\nnrows 1\nXLLCORNER inf\nyllcorner 0\ncellsize 1\n1\n";
    match parse_esri_ascii(text, "water.asc").unwrap_err() {
        DismechError::Grid(GridError::Header {
            file, key, value, ..
        }) => assert_eq!(
            (file.as_str(), key.as_str(), value.as_str()),
            ("water.asc", "XLLCORNER", "inf")
        ),
        e => panic!("{e}"),
    }
}

#[test]
fn nodata_nan_marks_the_cells_written_nan_as_missing() {
    // GIS tools write `NODATA_value nan` for float grids; such a file was
    // refused at its first missing cell.
    let text =
        "ncols 3\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\nNODATA_value nan\n1 NaN 3\n";
    let r = parse_esri_ascii(text, "slip.asc").unwrap();
    assert_eq!(r.values(), &[Some(1.0), None, Some(3.0)]);
}

#[test]
fn raster_from_fn_refuses_more_cells_than_the_cap_before_calling_f() {
    // 10^5 × 10^5 cells used to be collected into one allocation of
    // 1.6e11 bytes.
    let mut memory_and_result = None;
    let memory = allocation_counter::measure(|| {
        memory_and_result = Some(Raster::from_fn(100_000, 100_000, 0.0, 0.0, 1.0, |_, _| {
            panic!("f called")
        }));
    });
    assert!(matches!(
        memory_and_result.expect("ran"),
        Err(DismechError::InvalidParameter { .. })
    ));
    assert!(memory.bytes_max <= 64 * 1024, "{memory:?}");
}

#[test]
fn raster_new_refuses_a_size_whose_product_wraps_to_its_value_count() {
    // One value for 274177 × 67280421310721 cells (2^64 + 1, wrapping to
    // 1) used to make a raster whose `get` indexed out of bounds.
    let result = Raster::new(274_177, 67_280_421_310_721, 0.0, 0.0, 1.0, vec![Some(1.0)]);
    assert!(
        matches!(result, Err(DismechError::InvalidParameter { .. })),
        "{result:?}"
    );
}

/// The cause of a `GridFormat` refusal of `text`, with its line and column.
fn format_problem(text: &str) -> (usize, usize, GridFormatProblem) {
    match parse_esri_ascii(text, "g.asc").unwrap_err() {
        DismechError::Grid(GridError::Format {
            file,
            line,
            column,
            problem,
        }) => {
            assert_eq!(file, "g.asc");
            (line, column, problem)
        }
        e => panic!("{e}"),
    }
}

/// The cause of a `GridHeader` refusal of `text`, with its key.
fn header_problem(text: &str) -> (String, GridHeaderProblem) {
    match parse_esri_ascii(text, "g.asc").unwrap_err() {
        DismechError::Grid(GridError::Header {
            key, requirement, ..
        }) => (key, requirement),
        e => panic!("{e}"),
    }
}

#[test]
fn esri_grid_format_refusals_carry_a_typed_cause() {
    use GridFormatProblem as P;
    assert_eq!(format_problem(""), (0, 0, P::EndsInsideHeader));
    let key = "ncols".to_string();
    assert_eq!(format_problem("ncols"), (1, 1, P::KeyWithoutValue { key }));
    let key = "NCOLS".to_string();
    assert_eq!(
        format_problem("ncols 1\nNCOLS 2\n1"),
        (2, 1, P::KeyTwice { key })
    );
    let key = "cellsize";
    assert_eq!(
        format_problem("ncols 1\nnrows 1\nxllcorner 0\nyllcorner 0\n1"),
        (0, 0, P::MissingKey { key })
    );
    let key = "yllcorner or yllcenter";
    assert_eq!(
        format_problem("ncols 1\nnrows 1\nxllcorner 0\ncellsize 1\n1"),
        (0, 0, P::MissingKey { key })
    );
    let (columns, rows) = (2, 1);
    assert_eq!(
        format_problem(&grid("2", "1", "1 2 3")),
        (7, 5, P::TooManyValues { columns, rows })
    );
    assert_eq!(
        format_problem(&grid("2", "2", "1 2 3")),
        (
            0,
            0,
            P::TooFewValues {
                found: 3,
                columns: 2,
                rows: 2
            }
        )
    );
    let text = "x1".to_string();
    assert_eq!(
        format_problem(&grid("2", "2", "1 2\n3 x1")),
        (
            8,
            3,
            P::NotANumber {
                text,
                row: 1,
                column: 1
            }
        )
    );
    let text = "inf".to_string();
    assert_eq!(
        format_problem(&grid("2", "1", "inf 2")),
        (
            7,
            1,
            P::NotFinite {
                text,
                row: 0,
                column: 0
            }
        )
    );
}

#[test]
fn esri_grid_header_refusals_carry_a_typed_cause() {
    use GridHeaderProblem as P;
    let ncols = "ncols".to_string();
    assert_eq!(
        header_problem(&grid("1e30", "1", "1")),
        (ncols.clone(), P::NotWholeNumber)
    );
    assert_eq!(
        header_problem(&grid("0", "1", "1")),
        (ncols.clone(), P::Zero)
    );
    assert_eq!(
        header_problem(&grid("18446744073709551616", "1", "1")),
        (ncols, P::CountOverflow)
    );
    let head = |cell: &str, nodata: &str| {
        format!("ncols 1\nnrows 3\nxllcorner 0\nyllcorner 1e308\ncellsize {cell}\nNODATA_value {nodata}\n1 2 3\n")
    };
    let cellsize = "cellsize".to_string();
    assert_eq!(
        header_problem(&head("-1", "0")),
        (cellsize.clone(), P::NotPositive)
    );
    assert_eq!(
        header_problem(&head("inf", "0")),
        (cellsize.clone(), P::NotFinite)
    );
    assert_eq!(header_problem(&head("ten", "0")), (cellsize, P::NotANumber));
    assert_eq!(
        header_problem(&head("1e308", "0")),
        (
            "yllcorner".to_string(),
            P::ReachesInfinity {
                count: 3,
                cell_size: 1e308
            }
        )
    );
    assert_eq!(
        header_problem(&head("1", "none")),
        ("NODATA_value".to_string(), P::NotANumber)
    );
}
