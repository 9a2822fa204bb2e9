!> A case written to HDF5: provenance, the results of the output catalogue (veslide_quantities'
!> `case_results`: /scalars, /anisotropy, /patches, /persson) and the fields of its field
!> catalogue (/fields), under the root of a single run's file or under /cases/NNNNNN of a study.
!>
!> On a grid distributed over processes (the MPI build) the fields are written by every process
!> at once (parallel HDF5, `write_rows`), then the first process adds everything else, so the
!> file is laid out as a serial one. Both paths loop over the same field catalogue.
module veslide_case_file
    use veslide_kinds, only: dp, i8
    use veslide_error, only: error_t
    use veslide_collective, only: share_error
    use veslide_hdf5, only: h5file_t
    use veslide_hdf5_parallel, only: create_collective, write_rows
    use veslide_output, only: write_provenance
    use veslide_case_data, only: case_t
    use veslide_quantities, only: results_t, case_results, field_names, field_units, field_layout, case_field
    use veslide_warning, only: warning_t, WARNS_ABOVE, WARNS_BELOW
    implicit none
    private
    public :: write_case, write_case_group, write_results, write_warnings

contains

    !> Write one case to an HDF5 file (the caller writes to a temporary name, then commits);
    !> collective on a distributed grid
    subroutine write_case(path, c, error)
        character(len=*), intent(in) :: path
        type(case_t), intent(in), target :: c
        type(error_t), allocatable, intent(out) :: error
        type(h5file_t) :: f
        type(results_t) :: r
        integer :: k
        if (c%grid%is_distributed()) then
            call case_results(c, r)                 ! (collective: global sums and extrema)
            call create_collective(f, path, c%grid, error)
            if (c%spec%fields) then
                do k = 1, size(field_names)
                    if (.not. allocated(error)) &
                        call write_rows(f, c%grid, '/fields/'//trim(field_names(k)), case_field(c, k), error)
                end do
            end if
            if (allocated(error)) then
                call f%close()
            else
                call f%close(error)
            end if
            call share_error(c%grid, error); if (allocated(error)) return
            if (c%grid%is_root()) then
                call f%open(path, 'rw', error)
                if (.not. allocated(error)) call provenance(error)
                if (.not. allocated(error)) call write_case_group(f, '', c, error, r)
                if (allocated(error)) then
                    call f%close()
                else
                    call f%close(error)
                end if
            end if
            call share_error(c%grid, error)
            return
        end if
        call f%open(path, 'w', error); if (allocated(error)) return
        call provenance(error); if (allocated(error)) return
        call write_case_group(f, '', c, error); if (allocated(error)) return
        call f%close(error)
    contains
        subroutine provenance(error)
            type(error_t), allocatable, intent(out) :: error
            call write_provenance(f, c%spec%input_path, c%spec%input_text, [c%spec%surface%seed], error, &
                                  preparation=c%spec%surface%preparation)
        end subroutine provenance
    end subroutine write_case

    !> Results and fields of a case under `prefix` ('' for the root); on a distributed grid the
    !> fields are there already (written by every process) and get their attributes
    subroutine write_case_group(f, prefix, c, error, r)
        type(h5file_t), intent(inout) :: f
        character(len=*), intent(in) :: prefix
        type(case_t), intent(in), target :: c
        type(error_t), allocatable, intent(out) :: error
        !> the case's results, when the caller has them already
        type(results_t), intent(in), optional :: r
        type(results_t) :: r_
        character(len=:), allocatable :: name
        integer :: k
        if (present(r)) then
            r_ = r
        else
            call case_results(c, r_)
        end if
        call write_results(f, prefix, r_, error); if (allocated(error)) return
        if (allocated(c%warnings)) then
            call write_warnings(f, prefix, c%warnings, error); if (allocated(error)) return
        end if
        call f%writeattr(prefix//'/scalars', 'solver_method', c%state%method, error); if (allocated(error)) return
        call f%writeattr(prefix//'/scalars', 'kernel_variant', c%spec%kernel_name(), error)
        if (allocated(error)) return
        ! where it was solved ('cpu' or 'gpu'; the device itself: the root's provenance)
        call f%writeattr(prefix//'/scalars', 'device', c%state%device, error); if (allocated(error)) return
        if (c%state%device == 'gpu') then
            call f%writeattr(prefix//'/scalars', 'device_transfer_seconds', c%state%transfer_seconds, error)
            if (allocated(error)) return
        end if
        if (.not. c%spec%fields) return
        do k = 1, size(field_names)
            name = prefix//'/fields/'//trim(field_names(k))
            if (.not. c%grid%is_distributed()) then
                call f%write(name, case_field(c, k), error); if (allocated(error)) return
            end if
            call f%writeattr(name, 'units', trim(field_units(k)), error); if (allocated(error)) return
            call f%writeattr(name, 'layout', field_layout, error); if (allocated(error)) return
        end do
    end subroutine write_case_group

    !> The scalars of `r` under PREFIX/scalars/NAME (integers as int64) and its arrays under
    !> PREFIX/PATH, each with its `units` attribute (and `layout` where given)
    subroutine write_results(f, prefix, r, error)
        type(h5file_t), intent(inout) :: f
        character(len=*), intent(in) :: prefix
        type(results_t), intent(in) :: r
        type(error_t), allocatable, intent(out) :: error
        integer :: k
        character(len=:), allocatable :: name
        do k = 1, r%n
            associate (q => r%scalars(k))
                name = prefix//'/'//q%group//'/'//q%name
                if (q%is_integer) then
                    call f%write(name, nint(q%value, i8), error)
                else
                    call f%write(name, q%value, error)
                end if
                if (allocated(error)) return
                call f%writeattr(name, 'units', q%units, error); if (allocated(error)) return
                if (q%group == 'validity') then         ! its threshold, when it warns
                    select case (q%warns)
                    case (WARNS_ABOVE)
                        call f%writeattr(name, 'warns', 'above', error)
                    case (WARNS_BELOW)
                        call f%writeattr(name, 'warns', 'below', error)
                    case default
                        call f%writeattr(name, 'warns', 'never', error)
                    end select
                    if (allocated(error)) return
                    if (q%warns /= 0) call f%writeattr(name, 'threshold', q%threshold, error)
                    if (allocated(error)) return
                end if
            end associate
        end do
        do k = 1, r%na
            name = prefix//r%arrays(k)%path
            call f%write(name, r%arrays(k)%values, error); if (allocated(error)) return
            call f%writeattr(name, 'units', r%arrays(k)%units, error); if (allocated(error)) return
            if (len(r%arrays(k)%layout) > 0) call f%writeattr(name, 'layout', r%arrays(k)%layout, error)
            if (allocated(error)) return
        end do
    end subroutine write_results

    !> The warnings under PREFIX/warnings: five datasets of one entry per warning, in the order
    !> they were found: `code`, `source` ('input' or 'validity'), `text` (strings), `value` and
    !> `threshold` (float64; 0 where the warning is about a choice, not a number); empty when
    !> there are none. The group's attribute `count` is their number.
    subroutine write_warnings(f, prefix, warnings, error)
        type(h5file_t), intent(inout) :: f
        character(len=*), intent(in) :: prefix
        type(warning_t), intent(in) :: warnings(:)
        type(error_t), allocatable, intent(out) :: error
        character(len=:), allocatable :: codes(:), sources(:), texts(:)
        real(dp), allocatable :: values(:), thresholds(:)
        integer :: k, n, lc, lt
        n = size(warnings)
        lc = 1; lt = 1
        do k = 1, n
            lc = max(lc, len(warnings(k)%code), len(warnings(k)%source)); lt = max(lt, len(warnings(k)%text))
        end do
        allocate (character(len=lc) :: codes(n), sources(n))
        allocate (character(len=lt) :: texts(n))
        allocate (values(n), thresholds(n))
        do k = 1, n
            codes(k) = warnings(k)%code; sources(k) = warnings(k)%source; texts(k) = warnings(k)%text
            values(k) = warnings(k)%value; thresholds(k) = warnings(k)%threshold
        end do
        call f%write(prefix//'/warnings/code', codes, error); if (allocated(error)) return
        call f%write(prefix//'/warnings/source', sources, error); if (allocated(error)) return
        call f%write(prefix//'/warnings/text', texts, error); if (allocated(error)) return
        call f%write(prefix//'/warnings/value', values, error); if (allocated(error)) return
        call f%write(prefix//'/warnings/threshold', thresholds, error); if (allocated(error)) return
        call f%writeattr(prefix//'/warnings', 'count', int(n, i8), error)
    end subroutine write_warnings

end module veslide_case_file
