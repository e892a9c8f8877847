//! Failures of the linear solvers carry a typed cause
//! ([`FactorizationFailure`]) that a caller can match, and its message.

use dismech::linsolve::{
    BlockJacobi, FactorizationFailure, LinearSolver, Preconditioner, SolveError, SparseCholesky,
    SparseLu, SparseMatrix,
};

/// The cause of a `Factorization` error, or a panic.
fn cause(result: Result<impl std::fmt::Debug, SolveError>) -> FactorizationFailure {
    match result {
        Err(SolveError::Factorization(failure)) => failure,
        other => panic!("{other:?}"),
    }
}

/// `[[1, 2], [2, 1]]`: symmetric, indefinite, regular.
fn indefinite() -> SparseMatrix {
    SparseMatrix::from_triplets(2, &[(0, 0, 1.0), (0, 1, 2.0), (1, 0, 2.0), (1, 1, 1.0)]).unwrap()
}

#[test]
fn cholesky_of_an_indefinite_matrix_is_not_positive_definite() {
    let mut cholesky = SparseCholesky::new();
    let failure = cause(cholesky.factor(&indefinite()));
    assert!(
        matches!(failure, FactorizationFailure::NotPositiveDefinite { .. }),
        "{failure:?}"
    );
    let message = SolveError::Factorization(failure).to_string();
    assert!(message.contains("not positive definite"), "{message}");
}

#[test]
fn a_solve_before_any_factorization_is_not_factored() {
    let m = indefinite();
    let mut lu = SparseLu::default();
    assert_eq!(
        cause(lu.solve_in_place(&m, &mut [1.0, 1.0])),
        FactorizationFailure::NotFactored
    );
    let mut cholesky = SparseCholesky::new();
    assert_eq!(
        cause(cholesky.solve_in_place(&m, &mut [1.0, 1.0])),
        FactorizationFailure::NotFactored
    );
    assert_eq!(
        SolveError::Factorization(FactorizationFailure::NotFactored).to_string(),
        "factorization failed: solve before a factorization"
    );
}

#[test]
fn lu_of_a_singular_matrix_names_singularity() {
    // A free-free spring: a rigid-body mode.
    let free =
        SparseMatrix::from_triplets(2, &[(0, 0, 1.0), (0, 1, -1.0), (1, 0, -1.0), (1, 1, 1.0)])
            .unwrap();
    let mut lu = SparseLu::default();
    let failure = match lu.factor(&free) {
        Err(SolveError::Factorization(failure)) => failure,
        Ok(()) => cause(lu.solve_in_place(&free, &mut [1.0, 1.0])),
        Err(e) => panic!("{e}"),
    };
    assert!(
        matches!(
            failure,
            FactorizationFailure::StructurallySingular { .. }
                | FactorizationFailure::NumericallySingular { .. }
        ),
        "{failure:?}"
    );
    assert!(failure.to_string().contains("singular"), "{failure}");
}

#[test]
fn block_jacobi_with_an_indefinite_block_names_the_block() {
    let m = SparseMatrix::from_triplets(
        3,
        &[
            (0, 0, 2.0),
            (1, 0, 1.0),
            (0, 1, 1.0),
            (1, 1, 2.0),
            (2, 2, -1.0),
        ],
    )
    .unwrap();
    let mut jacobi = BlockJacobi::new(vec![0..2, 2..3]);
    let failure = cause(Preconditioner::<SparseMatrix>::setup(&mut jacobi, &m));
    assert_eq!(
        failure,
        FactorizationFailure::BlockNotPositiveDefinite { block: 1 }
    );
    assert_eq!(
        failure.to_string(),
        "block-Jacobi block 1 is not positive definite"
    );
}

#[test]
fn lp_failures_keep_the_messages_of_the_solver() {
    use dismech::linsolve::LpFailure;
    use dismech::lp::LpStatus;
    let setup = LpFailure::Setup {
        message: "bad dimensions".into(),
    };
    assert_eq!(
        SolveError::LinearProgram(setup).to_string(),
        "linear program solver error: bad dimensions"
    );
    let status = LpStatus::MaxIterations;
    assert_eq!(
        LpFailure::UniquenessTest { status }.to_string(),
        "the uniqueness test LP ended with status MaxIterations"
    );
}
