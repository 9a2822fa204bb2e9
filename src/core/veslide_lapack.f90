!> Explicit interfaces to the few BLAS/LAPACK routines veslide calls
module veslide_lapack
    use veslide_kinds, only: dp
    implicit none
    private
    public :: dposv, dgesv, dgels

    interface
        !> Solve A X = B for symmetric positive definite A (Cholesky)
        subroutine dposv(uplo, n, nrhs, a, lda, b, ldb, info)
            import :: dp
            character(len=1), intent(in) :: uplo
            integer, intent(in) :: n, nrhs, lda, ldb
            real(dp), intent(inout) :: a(lda, *), b(ldb, *)
            integer, intent(out) :: info
        end subroutine dposv
        !> Solve A X = B for a general A (LU with partial pivoting)
        subroutine dgesv(n, nrhs, a, lda, ipiv, b, ldb, info)
            import :: dp
            integer, intent(in) :: n, nrhs, lda, ldb
            real(dp), intent(inout) :: a(lda, *), b(ldb, *)
            integer, intent(out) :: ipiv(*), info
        end subroutine dgesv
        !> Least squares min |A X - B| for a general A of full rank (QR)
        subroutine dgels(trans, m, n, nrhs, a, lda, b, ldb, work, lwork, info)
            import :: dp
            character(len=1), intent(in) :: trans
            integer, intent(in) :: m, n, nrhs, lda, ldb, lwork
            real(dp), intent(inout) :: a(lda, *), b(ldb, *)
            real(dp), intent(out) :: work(*)
            integer, intent(out) :: info
        end subroutine dgels
    end interface

end module veslide_lapack
