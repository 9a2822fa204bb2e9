!> The HDF5 handle: datasets, attributes and tables read back as written, strings as UTF-8
module test_veslide_hdf5
    use veslide_kinds, only: dp, i8
    use veslide_hdf5, only: h5file_t
    use testsuite, only: error_t, unittest_t, new_unittest, check
    use test_support, only: unique_name, remove
    implicit none
    private
    public :: collect_hdf5

contains

    subroutine collect_hdf5(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("datasets-round-trip", test_datasets), &
            new_unittest("tables-mixed-columns-round-trip", test_tables), &
            new_unittest("copy-between-files", test_copy), &
            new_unittest("read-missing-dataset", test_missing, should_fail=.true., expect="no dataset /nothing") &
            ]
    end subroutine collect_hdf5


    subroutine test_datasets(error)
        type(error_t), allocatable, intent(out) :: error
        type(h5file_t) :: f
        character(len=:), allocatable :: path, text, attr
        real(dp) :: a(3, 2), b(3, 2), x
        integer(i8) :: i
        character(len=8) :: units(2)
        path = unique_name('rt.h5')
        a = reshape([1, 2, 3, 4, 5, 6]*0.5_dp, [3, 2])
        call f%open(path, 'w', error); if (allocated(error)) return
        call f%write('/g/a', a, error); if (allocated(error)) return
        call f%write('/g/x', 2.5_dp, error); if (allocated(error)) return
        call f%write('/g/i', 9007199254740993_i8, error); if (allocated(error)) return     ! 2^53 + 1
        call f%write('/g/t', 'ŝtring with ümlauts', error); if (allocated(error)) return
        call f%writeattr('/g/a', 'units', 'Pa', error); if (allocated(error)) return
        call f%writeattr('/g', 'list', [character(len=4) :: 'm', 'Pa'], error); if (allocated(error)) return
        call f%close(error); if (allocated(error)) return
        call f%open(path, 'r', error); if (allocated(error)) return
        call f%read_r2('/g/a', b, error); if (allocated(error)) return
        call f%read_r0('/g/x', x, error); if (allocated(error)) return
        call f%read_i0('/g/i', i, error); if (allocated(error)) return
        call f%read_text('/g/t', text, error); if (allocated(error)) return
        call f%read_attr_text('/g/a', 'units', attr, error); if (allocated(error)) return
        call f%read_attr_text_list('/g', 'list', units, error); if (allocated(error)) return
        call f%close()
        call remove(path)
        call check(error, all(a == b) .and. x == 2.5_dp, "reals"); if (allocated(error)) return
        call check(error, i == 9007199254740993_i8, "64-bit integer beyond 2^53"); if (allocated(error)) return
        call check(error, text == 'ŝtring with ümlauts' .and. attr == 'Pa', "strings"); if (allocated(error)) return
        call check(error, units(1) == 'm' .and. units(2) == 'Pa', "string list")
    end subroutine test_datasets

    !> Rows appended one by one (int64 and float64 columns) read back as a table with its units
    subroutine test_tables(error)
        type(error_t), allocatable, intent(out) :: error
        type(h5file_t) :: f
        character(len=:), allocatable :: path
        character(len=8), parameter :: cols(3) = [character(len=8) :: 'case', 'seed', 'f']
        character(len=8), parameter :: units(3) = [character(len=8) :: '-', '-', 'Pa']
        character(len=64), allocatable :: columns(:)
        character(len=8) :: units_back(3)
        logical, allocatable :: is_int(:)
        integer(i8), allocatable :: rows(:, :)
        integer :: k
        path = unique_name('table.h5')
        call f%open(path, 'w', error); if (allocated(error)) return
        do k = 1, 70                      ! more than one chunk of 64 rows
            call f%append_row('/summary', cols, units, [.true., .true., .false.], &
                              [int(k, i8), huge(1_i8) - k, transfer(0.1_dp*k, 0_i8)], error)
            if (allocated(error)) return
        end do
        call f%close(error); if (allocated(error)) return
        call f%open(path, 'r', error); if (allocated(error)) return
        call f%read_table('/summary', columns, is_int, rows, error); if (allocated(error)) return
        call f%read_attr_text_list('/summary', 'units', units_back, error); if (allocated(error)) return
        call f%close()
        call remove(path)
        call check(error, size(rows, 2) == 70 .and. all(columns(1:3) == cols), "shape and names")
        if (allocated(error)) return
        call check(error, all(is_int .eqv. [.true., .true., .false.]), "column types"); if (allocated(error)) return
        call check(error, rows(2, 70) == huge(1_i8) - 70 .and. transfer(rows(3, 7), 0.0_dp) == 0.1_dp*7, "values")
        if (allocated(error)) return
        call check(error, all(units_back == units), "units attribute")
    end subroutine test_tables

    subroutine test_copy(error)
        type(error_t), allocatable, intent(out) :: error
        type(h5file_t) :: a, b
        character(len=:), allocatable :: pa, pb
        real(dp) :: x
        pa = unique_name('copy-a.h5'); pb = unique_name('copy-b.h5')
        call a%open(pa, 'w', error); if (allocated(error)) return
        call a%write('/cases/000001/scalars/x', 4.0_dp, error); if (allocated(error)) return
        call a%close()
        call a%open(pa, 'r', error); if (allocated(error)) return
        call b%open(pb, 'w', error); if (allocated(error)) return
        call b%copy_from(a, '/cases/000001', '/cases/000001', error); if (allocated(error)) return
        call a%close(); call b%close()
        call b%open(pb, 'r', error); if (allocated(error)) return
        call b%read_r0('/cases/000001/scalars/x', x, error); if (allocated(error)) return
        call b%close()
        call remove(pa); call remove(pb)
        call check(error, x == 4.0_dp, "copied value")
    end subroutine test_copy

    subroutine test_missing(error)
        type(error_t), allocatable, intent(out) :: error
        type(h5file_t) :: f
        character(len=:), allocatable :: path
        real(dp) :: x
        path = unique_name('missing.h5')
        call f%open(path, 'w', error); if (allocated(error)) return
        call f%read_r0('/nothing', x, error)
        call f%close()
        call remove(path)
    end subroutine test_missing

end module test_veslide_hdf5
